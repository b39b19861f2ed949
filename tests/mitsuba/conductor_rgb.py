"""Prints Mitsuba 3's RGB (scalar_rgb) eta and k for the named conductor presets that
lightlab's src/bsdf/conductor_ior.rs tabulates. Run: python3 tests/mitsuba/conductor_rgb.py"""
import mitsuba as mi

mi.set_variant("scalar_rgb")
for name in ["Au", "Ag", "Cu", "Al", "Cr"]:
    bsdf = mi.load_dict({"type": "conductor", "material": name})
    params = mi.traverse(bsdf)
    print(name, "eta", params["eta.value"], "k", params["k.value"])
