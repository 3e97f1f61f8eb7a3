/* Renders the seeded terrain (size 100, seed 1) from the paper's camera
 * to a binary PPM: the bytes `voxtrace --seed 1 --size 100 --width 320
 * --height 180 --position 90,90,90 --lookat 0,0,0` writes as PPM.
 *
 *   cc examples/terrain.c -Iinclude -L../../target/release -lvoxtrace_capi -o terrain
 *   LD_LIBRARY_PATH=../../target/release ./terrain terrain.ppm
 */
#include <stdio.h>
#include <stdlib.h>

#include "voxtrace.h"

/* Prints the last call's message and returns 1. */
static int fail(const char *what) {
    char message[512];
    vt_last_error(message, sizeof message);
    fprintf(stderr, "%s: %s\n", what, message);
    return 1;
}

int main(int argc, char **argv) {
    const char *out = argc > 1 ? argv[1] : "terrain.ppm";
    VtScene *scene = NULL;
    if (vt_scene_terrain(100, 1, VT_BACKEND_OCTREE, &scene) != VT_STATUS_OK) return fail("terrain");
    VtView view = {320, 180, {90.0f, 90.0f, 90.0f}, {0.0f, 0.0f, 0.0f}, 0.0f};
    size_t len = (size_t)view.width * view.height * 4;
    unsigned char *rgba = malloc(len);
    if (rgba == NULL) return 1;
    if (vt_render(scene, &view, NULL, 0, rgba, len) != VT_STATUS_OK) return fail("render");
    /* A refused call: the buffer is one byte short. */
    if (vt_render(scene, &view, NULL, 1, rgba, len - 1) != VT_STATUS_INVALID_ARGUMENT) return 1;
    vt_scene_free(scene);
    FILE *file = fopen(out, "wb");
    if (file == NULL) return 1;
    fprintf(file, "P6\n%u %u 255\n", view.width, view.height);
    for (size_t i = 0; i < len; i += 4) fwrite(rgba + i, 1, 3, file);
    fclose(file);
    free(rgba);
    return 0;
}
