/* Embree's single rays and its 8-wide packets (rtcIntersect1, rtcIntersect8) on the mesh
 * and primary rays that examples/bvh_compare.rs dumps, so lightlab's closest-hit rate on
 * coherent camera rays can be quoted against Embree's packet traversal (issue 13).
 *
 *   cargo run --release --features obvhs-compare --example bvh_compare -- --dump DIR
 *   apt-get install libembree-dev          # Debian ships Embree 3.13
 *   cc -O2 -o target/embree_packets benches/embree_packets.c -lembree3 -lpthread
 *   target/embree_packets DIR
 *   target/embree_packets DIR --builds N [THREADS]   # build times only (see below)
 *
 * The primary rays are in scanline order over a square grid of pixels, so eight
 * consecutive rays (eight neighbouring pixels of a row) make a coherent packet, flagged
 * RTC_INTERSECT_CONTEXT_FLAG_COHERENT. Embree's interval is [tnear, tfar] with tnear = 0,
 * lightlab's (0, t_max), so a hit count may differ by a ray at distance 0. Rates are medians of 5 runs, on 1 and 2 threads
 * (each thread takes an equal share of the rays); hit counts are printed to compare with
 * bvh_compare's.
 *
 * With --builds N the program only builds: each mesh N times on a device of THREADS
 * threads (default: all), printing the median of rtcCommitScene's wall time with the
 * scene's creation, to set against examples/bvh_build.rs's medians.
 */
#include <embree3/rtcore.h>
#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#define RUNS 5

static void *read_file(const char *dir, const char *name, const char *kind, size_t *bytes) {
    char path[4096];
    snprintf(path, sizeof path, "%s/%s.%s", dir, name, kind);
    FILE *f = fopen(path, "rb");
    if (!f) {
        fprintf(stderr, "embree_packets: cannot open %s\n", path);
        exit(1);
    }
    fseek(f, 0, SEEK_END);
    *bytes = (size_t)ftell(f);
    fseek(f, 0, SEEK_SET);
    /* Embree reads vertex buffers 16 bytes at a time: keep slack after the last one. */
    void *data = calloc(1, *bytes + 16);
    if (!data || fread(data, 1, *bytes, f) != *bytes) {
        fprintf(stderr, "embree_packets: cannot read %s\n", path);
        exit(1);
    }
    fclose(f);
    return data;
}

static double now(void) {
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec + 1e-9 * t.tv_nsec;
}

struct job {
    RTCScene scene;
    const float *rays; /* 7 floats per ray: origin, direction, t_max */
    size_t first, count;
    int packets;
    size_t hits;
};

static void *trace(void *arg) {
    struct job *j = arg;
    struct RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    j->hits = 0;
    if (!j->packets) {
        for (size_t i = j->first; i < j->first + j->count; i++) {
            const float *r = j->rays + 7 * i;
            struct RTCRayHit rh;
            memset(&rh, 0, sizeof rh);
            rh.ray.org_x = r[0], rh.ray.org_y = r[1], rh.ray.org_z = r[2];
            rh.ray.dir_x = r[3], rh.ray.dir_y = r[4], rh.ray.dir_z = r[5];
            rh.ray.tnear = 0.0f, rh.ray.tfar = r[6], rh.ray.mask = -1;
            rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
            rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
            rtcIntersect1(j->scene, &ctx, &rh);
            j->hits += rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
        }
        return NULL;
    }
    ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    for (size_t i = j->first; i < j->first + j->count; i += 8) {
        struct RTCRayHit8 rh __attribute__((aligned(32)));
        int valid[8] __attribute__((aligned(32)));
        memset(&rh, 0, sizeof rh);
        for (int k = 0; k < 8; k++) {
            size_t n = i + k;
            valid[k] = n < j->first + j->count ? -1 : 0;
            if (!valid[k]) continue;
            const float *r = j->rays + 7 * n;
            rh.ray.org_x[k] = r[0], rh.ray.org_y[k] = r[1], rh.ray.org_z[k] = r[2];
            rh.ray.dir_x[k] = r[3], rh.ray.dir_y[k] = r[4], rh.ray.dir_z[k] = r[5];
            rh.ray.tnear[k] = 0.0f, rh.ray.tfar[k] = r[6], rh.ray.mask[k] = -1;
            rh.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
            rh.hit.instID[0][k] = RTC_INVALID_GEOMETRY_ID;
        }
        rtcIntersect8(valid, j->scene, &ctx, &rh);
        for (int k = 0; k < 8; k++)
            j->hits += valid[k] && rh.hit.geomID[k] != RTC_INVALID_GEOMETRY_ID;
    }
    return NULL;
}

static int cmp_double(const void *a, const void *b) {
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Median Mrays/s of tracing every ray on `threads` threads; *hits gets the hit count. */
static double rate(RTCScene scene, const float *rays, size_t n, int threads, int packets,
                   size_t *hits) {
    double seconds[RUNS];
    for (int run = 0; run < RUNS; run++) {
        struct job jobs[2];
        pthread_t ids[2];
        /* Shares start at multiples of 8, so packets stay within one row's run of rays. */
        size_t share = ((n + threads - 1) / threads + 7) / 8 * 8;
        double start = now();
        for (int t = 0; t < threads; t++) {
            size_t first = share * t;
            size_t count = first >= n ? 0 : (n - first < share ? n - first : share);
            jobs[t] = (struct job){scene, rays, first, count, packets, 0};
            pthread_create(&ids[t], NULL, trace, &jobs[t]);
        }
        *hits = 0;
        for (int t = 0; t < threads; t++) {
            pthread_join(ids[t], NULL);
            *hits += jobs[t].hits;
        }
        seconds[run] = now() - start;
    }
    qsort(seconds, RUNS, sizeof seconds[0], cmp_double);
    return n / seconds[RUNS / 2] / 1e6;
}

/* Median wall time of `runs` builds of each mesh (the --builds mode). */
static int builds(const char *dir, int runs, int threads) {
    char config[64] = "";
    if (threads > 0) snprintf(config, sizeof config, "threads=%d", threads);
    RTCDevice device = rtcNewDevice(config);
    printf("| mesh | Embree %d.%d.%d build s, %s threads, median of %d |\n", RTC_VERSION_MAJOR,
           RTC_VERSION_MINOR, RTC_VERSION_PATCH, threads > 0 ? config + 8 : "all", runs);
    printf("|---|---|\n");
    const char *names[] = {"100k", "1M"};
    double *times = calloc((size_t)runs, sizeof(double));
    for (int m = 0; m < 2; m++) {
        size_t vbytes, ibytes;
        float *vertices = read_file(dir, names[m], "vertices.f32", &vbytes);
        unsigned *indices = read_file(dir, names[m], "indices.u32", &ibytes);
        for (int r = 0; r < runs; r++) {
            double start = now();
            RTCScene scene = rtcNewScene(device);
            RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
            rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                       vertices, 0, 12, vbytes / 12);
            rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, indices,
                                       0, 12, ibytes / 12);
            rtcCommitGeometry(geom);
            rtcAttachGeometry(scene, geom);
            rtcReleaseGeometry(geom);
            rtcCommitScene(scene);
            times[r] = now() - start;
            rtcReleaseScene(scene);
        }
        qsort(times, (size_t)runs, sizeof(double), cmp_double);
        printf("| %s | %.3f |\n", names[m], times[runs / 2]);
        free(vertices), free(indices);
    }
    free(times);
    rtcReleaseDevice(device);
    return 0;
}

int main(int argc, char **argv) {
    if ((argc == 4 || argc == 5) && strcmp(argv[2], "--builds") == 0 && atoi(argv[3]) > 0) {
        return builds(argv[1], atoi(argv[3]), argc == 5 ? atoi(argv[4]) : 0);
    }
    if (argc != 2 || strcmp(argv[1], "--builds") == 0) {
        fprintf(stderr, "usage: embree_packets DIR [--builds N [THREADS]] (DIR from bvh_compare --dump DIR)\n");
        return 2;
    }
    RTCDevice device = rtcNewDevice(NULL);
    printf("| mesh | Embree %d.%d.%d | build s | closest Mrays/s 1 thr | 2 thr | primary hits |\n",
           RTC_VERSION_MAJOR, RTC_VERSION_MINOR, RTC_VERSION_PATCH);
    printf("|---|---|---|---|---|---|\n");
    const char *names[] = {"100k", "1M"};
    for (int m = 0; m < 2; m++) {
        size_t vbytes, ibytes, rbytes;
        float *vertices = read_file(argv[1], names[m], "vertices.f32", &vbytes);
        unsigned *indices = read_file(argv[1], names[m], "indices.u32", &ibytes);
        float *rays = read_file(argv[1], names[m], "primary.f32", &rbytes);
        size_t nv = vbytes / 12, nt = ibytes / 12, nr = rbytes / 28;
        double start = now();
        RTCScene scene = rtcNewScene(device);
        RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
        rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, vertices,
                                   0, 12, nv);
        rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, indices, 0,
                                   12, nt);
        rtcCommitGeometry(geom);
        rtcAttachGeometry(scene, geom);
        rtcReleaseGeometry(geom);
        rtcCommitScene(scene);
        double build = now() - start;
        for (int packets = 0; packets < 2; packets++) {
            size_t hits1, hits2;
            double r1 = rate(scene, rays, nr, 1, packets, &hits1);
            double r2 = rate(scene, rays, nr, 2, packets, &hits2);
            if (hits1 != hits2) {
                fprintf(stderr, "embree_packets: %zu hits on 1 thread, %zu on 2\n", hits1, hits2);
                return 1;
            }
            printf("| %s (%zu tris) | %s | %.3f | %.2f | %.2f | %zu |\n", names[m], nt,
                   packets ? "rtcIntersect8 (coherent)" : "rtcIntersect1", build, r1, r2, hits1);
        }
        rtcReleaseScene(scene);
        free(vertices), free(indices), free(rays);
    }
    rtcReleaseDevice(device);
    return 0;
}
