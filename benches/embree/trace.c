/* Intel Embree on voxtrace's terrain: the mesh, rays and hits that
 * `voxtrace-report embree-input` wrote (see its docs for the format),
 * traced on one thread with rtcIntersect1 (a ray per call), rtcIntersect8
 * (4x2 pixel tiles) and rtcIntersect16 (4x4 tiles). Prints, per way, the
 * median tracing time of RUNS runs (tracing only: no ray generation from
 * a camera, no shading) and the share of pixels whose hit voxel differs
 * from voxtrace's.
 *
 * Build: cc -O2 -o trace trace.c -lembree3
 * Run:   ./trace DIR [RUNS]
 */
#include <embree3/rtcore.h>
#include <float.h>
#include <limits.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static void *read_file(const char *dir, const char *name, size_t *len) {
    char path[4096];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    FILE *f = fopen(path, "rb");
    if (!f) { fprintf(stderr, "error: cannot open %s\n", path); exit(2); }
    fseek(f, 0, SEEK_END);
    *len = (size_t)ftell(f);
    fseek(f, 0, SEEK_SET);
    void *bytes = malloc(*len);
    if (!bytes || fread(bytes, 1, *len, f) != *len) { fprintf(stderr, "error: cannot read %s\n", path); exit(2); }
    fclose(f);
    return bytes;
}

static double now(void) {
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec + t.tv_nsec * 1e-9;
}

static int compare_doubles(const void *a, const void *b) {
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

typedef struct { float o[3], d[3]; } Ray;

/* The voxel each pixel hit, from the triangle (INT_MIN: a miss). */
static const int32_t *voxel_of;
static void record(int32_t *out, unsigned prim, int hit) {
    for (int k = 0; k < 3; k++) out[k] = hit ? voxel_of[3 * (size_t)prim + k] : INT_MIN;
}

int main(int argc, char **argv) {
    if (argc < 2) { fprintf(stderr, "usage: trace DIR [RUNS]\n"); return 2; }
    const char *dir = argv[1];
    int runs = argc > 2 ? atoi(argv[2]) : 5;
    size_t len;
    uint32_t *mesh = read_file(dir, "mesh.bin", &len);
    uint32_t nv = mesh[0], nt = mesh[1];
    const float *vertices = (const float *)(mesh + 2);
    const uint32_t *indices = mesh + 2 + 3 * (size_t)nv;
    voxel_of = (const int32_t *)(indices + 3 * (size_t)nt);
    uint32_t *rays_file = read_file(dir, "rays.bin", &len);
    uint32_t w = rays_file[0], h = rays_file[1];
    const Ray *rays = (const Ray *)(rays_file + 2);
    int32_t *expected = read_file(dir, "hits.bin", &len);
    size_t n = (size_t)w * h;
    int32_t *got = malloc(n * 3 * sizeof *got);

    RTCDevice device = rtcNewDevice("threads=1");
    RTCScene scene = rtcNewScene(device);
    rtcSetSceneBuildQuality(scene, RTC_BUILD_QUALITY_HIGH);
    RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    float *vb = rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), nv);
    memcpy(vb, vertices, 3 * sizeof(float) * nv);
    unsigned *ib = rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), nt);
    memcpy(ib, indices, 3 * sizeof(unsigned) * nt);
    rtcCommitGeometry(geom);
    rtcAttachGeometry(scene, geom);
    rtcReleaseGeometry(geom);
    double build0 = now();
    rtcCommitScene(scene);
    double build = now() - build0;

    const char *names[3] = {"rtcIntersect1", "rtcIntersect8 (4x2 tiles)", "rtcIntersect16 (4x4 tiles)"};
    const int tw[3] = {1, 4, 4}, th[3] = {1, 2, 4};
    printf("embree: %u triangles, %ux%u rays, build %.1f ms (one thread)\n", nt, w, h, build * 1e3);
    printf("| way | median ms | rays/s per core | hits differing from voxtrace |\n|---|---|---|---|\n");
    double *times = malloc(sizeof(double) * (size_t)runs);
    for (int way = 0; way < 3; way++) {
        for (int r = 0; r < runs; r++) {
            double t0 = now();
            struct RTCIntersectContext context;
            rtcInitIntersectContext(&context);
            for (uint32_t ty = 0; ty < h; ty += th[way]) {
                for (uint32_t tx = 0; tx < w; tx += tw[way]) {
                    if (way == 0) {
                        size_t i = (size_t)ty * w + tx;
                        struct RTCRayHit rh;
                        rh.ray.org_x = rays[i].o[0]; rh.ray.org_y = rays[i].o[1]; rh.ray.org_z = rays[i].o[2];
                        rh.ray.dir_x = rays[i].d[0]; rh.ray.dir_y = rays[i].d[1]; rh.ray.dir_z = rays[i].d[2];
                        rh.ray.tnear = 0.0f; rh.ray.tfar = FLT_MAX; rh.ray.mask = -1; rh.ray.flags = 0; rh.ray.time = 0.0f;
                        rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
                        rtcIntersect1(scene, &context, &rh);
                        record(got + 3 * i, rh.hit.primID, rh.hit.geomID != RTC_INVALID_GEOMETRY_ID);
                    } else {
                        int lanes = tw[way] * th[way];
                        int valid[16];
                        size_t index[16];
                        struct RTCRayHit16 rh; /* also holds 8 lanes: the same layout, first 8 used */
                        struct RTCRayHit8 rh8;
                        for (int k = 0; k < lanes; k++) {
                            uint32_t x = tx + k % tw[way], y = ty + k / tw[way];
                            valid[k] = (x < w && y < h) ? -1 : 0;
                            size_t i = valid[k] ? (size_t)y * w + x : 0;
                            index[k] = i;
                            if (way == 1) {
                                rh8.ray.org_x[k] = rays[i].o[0]; rh8.ray.org_y[k] = rays[i].o[1]; rh8.ray.org_z[k] = rays[i].o[2];
                                rh8.ray.dir_x[k] = rays[i].d[0]; rh8.ray.dir_y[k] = rays[i].d[1]; rh8.ray.dir_z[k] = rays[i].d[2];
                                rh8.ray.tnear[k] = 0.0f; rh8.ray.tfar[k] = FLT_MAX; rh8.ray.mask[k] = -1; rh8.ray.flags[k] = 0; rh8.ray.time[k] = 0.0f;
                                rh8.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
                            } else {
                                rh.ray.org_x[k] = rays[i].o[0]; rh.ray.org_y[k] = rays[i].o[1]; rh.ray.org_z[k] = rays[i].o[2];
                                rh.ray.dir_x[k] = rays[i].d[0]; rh.ray.dir_y[k] = rays[i].d[1]; rh.ray.dir_z[k] = rays[i].d[2];
                                rh.ray.tnear[k] = 0.0f; rh.ray.tfar[k] = FLT_MAX; rh.ray.mask[k] = -1; rh.ray.flags[k] = 0; rh.ray.time[k] = 0.0f;
                                rh.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
                            }
                        }
                        if (way == 1) rtcIntersect8(valid, scene, &context, &rh8);
                        else rtcIntersect16(valid, scene, &context, &rh);
                        for (int k = 0; k < lanes; k++) {
                            if (!valid[k]) continue;
                            unsigned geom_id = way == 1 ? rh8.hit.geomID[k] : rh.hit.geomID[k];
                            unsigned prim = way == 1 ? rh8.hit.primID[k] : rh.hit.primID[k];
                            record(got + 3 * index[k], prim, geom_id != RTC_INVALID_GEOMETRY_ID);
                        }
                    }
                }
            }
            times[r] = now() - t0;
        }
        qsort(times, (size_t)runs, sizeof *times, compare_doubles);
        double median = times[runs / 2];
        size_t differ = 0;
        for (size_t i = 0; i < n; i++) differ += memcmp(got + 3 * i, expected + 3 * i, 3 * sizeof *got) != 0;
        printf("| %s | %.1f | %.2f M | %.3f%% (%zu) |\n", names[way], median * 1e3, n / median / 1e6,
               100.0 * differ / n, differ);
    }
    rtcReleaseScene(scene);
    rtcReleaseDevice(device);
    return 0;
}
