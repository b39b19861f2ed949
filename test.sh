#!/usr/bin/env bash
# The one test command: the Rust tests, then the Python package built into a venv under
# target/ and its pytest suite. Needs cargo, python3 (>= 3.9, with the venv module) and
# access to crates.io and PyPI. Exits non-zero on any failure.
set -euo pipefail
cd "$(dirname "$0")"

# The release profile without its LTO (see Cargo.toml): the same results, a third of the
# build time.
cargo test --profile test-release

start=$SECONDS
venv=target/py-venv
if [ ! -x "$venv/bin/python" ]; then
    python3 -m venv "$venv"
fi
"$venv/bin/pip" install --quiet "dask[distributed]" pytest numpy
# The extension builds into its own target dir, so the root build is left as it is.
CARGO_TARGET_DIR="$PWD/target/python" \
    "$venv/bin/pip" install --quiet --force-reinstall --no-deps ./python
built=$SECONDS
# From python/tests, `import lightlab` is the installed package, not python/lightlab.
(cd python/tests && ../../"$venv"/bin/python -m pytest -q -p no:cacheprovider .)
echo "python: install $((built - start)) s, tests $((SECONDS - built)) s"
