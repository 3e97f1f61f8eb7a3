/* Intel Embree on voxtrace's terrain: the mesh, rays and hits that
 * `voxtrace-report embree-input` wrote (see its docs for the format),
 * traced on one thread with rtcIntersect1 (a ray per call), rtcIntersect8
 * (4x2 pixel tiles) and rtcIntersect16 (4x4 tiles). Prints, per way, the
 * median tracing time of RUNS runs (tracing only: no ray generation from
 * a camera, no shading) and the share of pixels whose hit voxel differs
 * from voxtrace's.
 *
 *
 * With `secondary` (after `voxtrace-report embree-input --occlusion N`),
 * instead the occlusion rays of those hits that `voxtrace --ao N` traces
 * (occlusion.bin), with rtcOccluded1, rtcOccluded8 and rtcOccluded16 up
 * to their reach, then the same rays unbounded with rtcIntersect1 and
 * rtcIntersect16. Packets take the rays 8 or 16 at a time in the order
 * they come (a pixel's rays in turn, pixels row by row: 2 or 4 hits a
 * packet), as a packet tracer handed a frame's secondary rays gets them;
 * nothing sorts them. Prints, per way, the median tracing time and the
 * rays whose answer differs from voxtrace's (occlusion: blocked or open;
 * unbounded: hit or miss, and where both hit, the voxel and the distance).
 *
 * Build: cc -O2 -o trace trace.c -lembree3
 * Run:   ./trace DIR [RUNS] [camera|secondary]
 */
#include <embree3/rtcore.h>
#include <float.h>
#include <limits.h>
#include <math.h>
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

static int secondary(RTCScene scene, const char *dir, int runs);

int main(int argc, char **argv) {
    if (argc < 2) { fprintf(stderr, "usage: trace DIR [RUNS] [camera|secondary]\n"); return 2; }
    const char *dir = argv[1];
    int runs = argc > 2 ? atoi(argv[2]) : 5;
    int camera = argc <= 3 || strcmp(argv[3], "secondary") != 0;
    if (runs < 1 || (argc > 3 && camera && strcmp(argv[3], "camera") != 0)) {
        fprintf(stderr, "usage: trace DIR [RUNS] [camera|secondary]\n");
        return 2;
    }
    size_t len;
    uint32_t *mesh = read_file(dir, "mesh.bin", &len);
    uint32_t nv = mesh[0], nt = mesh[1];
    const float *vertices = (const float *)(mesh + 2);
    const uint32_t *indices = mesh + 2 + 3 * (size_t)nv;
    voxel_of = (const int32_t *)(indices + 3 * (size_t)nt);

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
    if (!camera) {
        printf("embree: %u triangles, build %.1f ms (one thread)\n", nt, build * 1e3);
        int status = secondary(scene, dir, runs);
        rtcReleaseScene(scene);
        rtcReleaseDevice(device);
        return status;
    }

    uint32_t *rays_file = read_file(dir, "rays.bin", &len);
    uint32_t w = rays_file[0], h = rays_file[1];
    const Ray *rays = (const Ray *)(rays_file + 2);
    int32_t *expected = read_file(dir, "hits.bin", &len);
    size_t n = (size_t)w * h;
    int32_t *got = malloc(n * 3 * sizeof *got);
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

/* voxtrace's answers for one occlusion ray (occlusion_hits.bin). */
typedef struct { uint32_t blocked; float t; int32_t voxel[3]; } Answer;

/* Embree's answer for one ray: blocked (occlusion) or the hit's distance
 * and triangle (unbounded; t infinite for a miss). */
typedef struct { float t; unsigned prim; } Got;

/* Fills lane k of a packet of 8 or 16 rays (P: RTCRay8 or RTCRay16). */
#define SET_LANE(P, k, r, tmax) do { \
    (P).org_x[k] = (r).o[0]; (P).org_y[k] = (r).o[1]; (P).org_z[k] = (r).o[2]; \
    (P).dir_x[k] = (r).d[0]; (P).dir_y[k] = (r).d[1]; (P).dir_z[k] = (r).d[2]; \
    (P).tnear[k] = 0.0f; (P).tfar[k] = (tmax); (P).mask[k] = -1; (P).flags[k] = 0; (P).time[k] = 0.0f; \
} while (0)

static void set_ray(struct RTCRay *ray, const Ray *r, float tmax) {
    ray->org_x = r->o[0]; ray->org_y = r->o[1]; ray->org_z = r->o[2];
    ray->dir_x = r->d[0]; ray->dir_y = r->d[1]; ray->dir_z = r->d[2];
    ray->tnear = 0.0f; ray->tfar = tmax; ray->mask = -1; ray->flags = 0; ray->time = 0.0f;
}

/* One pass of way `way` over the n rays into got[]. */
static void trace_secondary(RTCScene scene, int way, const Ray *rays, size_t n, float reach, Got *got) {
    struct RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    const float inf = INFINITY;
    switch (way) {
    case 0: /* rtcOccluded1 */
        for (size_t i = 0; i < n; i++) {
            struct RTCRay ray;
            set_ray(&ray, rays + i, reach);
            rtcOccluded1(scene, &context, &ray);
            got[i].t = ray.tfar;
        }
        break;
    case 1: /* rtcOccluded8 */
        for (size_t i = 0; i < n; i += 8) {
            int valid[8];
            struct RTCRay8 ray;
            for (int k = 0; k < 8; k++) {
                valid[k] = i + k < n ? -1 : 0;
                SET_LANE(ray, k, rays[valid[k] ? i + k : i], reach);
            }
            rtcOccluded8(valid, scene, &context, &ray);
            for (int k = 0; k < 8 && i + k < n; k++) got[i + k].t = ray.tfar[k];
        }
        break;
    case 2: /* rtcOccluded16 */
        for (size_t i = 0; i < n; i += 16) {
            int valid[16];
            struct RTCRay16 ray;
            for (int k = 0; k < 16; k++) {
                valid[k] = i + k < n ? -1 : 0;
                SET_LANE(ray, k, rays[valid[k] ? i + k : i], reach);
            }
            rtcOccluded16(valid, scene, &context, &ray);
            for (int k = 0; k < 16 && i + k < n; k++) got[i + k].t = ray.tfar[k];
        }
        break;
    case 3: /* rtcIntersect1, unbounded */
        for (size_t i = 0; i < n; i++) {
            struct RTCRayHit rh;
            set_ray(&rh.ray, rays + i, inf);
            rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
            rtcIntersect1(scene, &context, &rh);
            int hit = rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
            got[i].t = hit ? rh.ray.tfar : inf;
            got[i].prim = rh.hit.primID;
        }
        break;
    case 4: /* rtcIntersect16, unbounded */
        for (size_t i = 0; i < n; i += 16) {
            int valid[16];
            struct RTCRayHit16 rh;
            for (int k = 0; k < 16; k++) {
                valid[k] = i + k < n ? -1 : 0;
                SET_LANE(rh.ray, k, rays[valid[k] ? i + k : i], inf);
                rh.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
            }
            rtcIntersect16(valid, scene, &context, &rh);
            for (int k = 0; k < 16 && i + k < n; k++) {
                int hit = rh.hit.geomID[k] != RTC_INVALID_GEOMETRY_ID;
                got[i + k].t = hit ? rh.ray.tfar[k] : inf;
                got[i + k].prim = rh.hit.primID[k];
            }
        }
        break;
    }
}

static int secondary(RTCScene scene, const char *dir, int runs) {
    size_t len;
    uint32_t *file = read_file(dir, "occlusion.bin", &len);
    size_t n = file[0];
    float reach;
    memcpy(&reach, file + 1, sizeof reach);
    uint32_t per_hit = file[2], unsent = file[3];
    const Ray *rays = (const Ray *)(file + 4);
    const Answer *expected = read_file(dir, "occlusion_hits.bin", &len);
    if (len != n * sizeof *expected) { fprintf(stderr, "error: occlusion_hits.bin does not match occlusion.bin\n"); return 2; }
    Got *got = malloc(n * sizeof *got);
    size_t blocked = 0, hits = 0;
    for (size_t i = 0; i < n; i++) blocked += expected[i].blocked != 0, hits += isfinite(expected[i].t);
    printf("occlusion rays: %zu (%u a hit, reach %g; %u that cannot leave their face not traced), "
           "voxtrace: %zu blocked within the reach, %zu hit unbounded\n",
           n, per_hit, reach, unsent, blocked, hits);
    printf("| way | median ms | rays/s per core | answers differing from voxtrace |\n|---|---|---|---|\n");
    const char *names[5] = {"rtcOccluded1 (to the reach)", "rtcOccluded8 (to the reach)",
                            "rtcOccluded16 (to the reach)", "rtcIntersect1 (unbounded)",
                            "rtcIntersect16 (unbounded)"};
    double *times = malloc(sizeof(double) * (size_t)runs);
    for (int way = 0; way < 5; way++) {
        for (int r = 0; r < runs; r++) {
            double t0 = now();
            trace_secondary(scene, way, rays, n, reach, got);
            times[r] = now() - t0;
        }
        qsort(times, (size_t)runs, sizeof *times, compare_doubles);
        double median = times[runs / 2];
        char differ[256];
        if (way < 3) {
            /* rtcOccluded sets tfar to -inf where the ray meets a triangle. */
            size_t d = 0;
            for (size_t i = 0; i < n; i++) d += (got[i].t < 0.0f) != (expected[i].blocked != 0);
            snprintf(differ, sizeof differ, "%.4f%% (%zu) open/blocked", 100.0 * d / n, d);
        } else {
            /* Hit or miss; where both hit, the voxel; where both hit the
             * same voxel, the distance, beyond 1e-4 relative (1e-4
             * absolute under 1). */
            size_t d = 0, voxel = 0, far = 0;
            double worst = 0.0;
            for (size_t i = 0; i < n; i++) {
                int theirs = isfinite(got[i].t), ours = isfinite(expected[i].t);
                if (theirs != ours) { d++; continue; }
                if (!ours) continue;
                const int32_t *v = voxel_of + 3 * (size_t)got[i].prim;
                if (memcmp(v, expected[i].voxel, sizeof expected[i].voxel) != 0) { voxel++; continue; }
                double dt = fabs((double)got[i].t - expected[i].t);
                if (dt > worst) worst = dt;
                far += dt > 1e-4 * fmax(1.0, expected[i].t);
            }
            snprintf(differ, sizeof differ,
                     "%.4f%% (%zu) hit/miss; %zu other voxels; %zu distances off (largest %.2g)",
                     100.0 * d / n, d, voxel, far, worst);
        }
        printf("| %s | %.1f | %.2f M | %s |\n", names[way], median * 1e3, n / median / 1e6, differ);
        fflush(stdout);
    }
    free(times);
    free(got);
    return 0;
}
