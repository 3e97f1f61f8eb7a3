/* Renders the seeded terrain (size 100, seed 1) from the paper's camera
 * to a binary PPM, the bytes `voxtrace --seed 1 --size 100 --width 320
 * --height 180 --position 90,90,90 --lookat 0,0,0 --format ppm` writes;
 * given a .vox file too, renders it from the CLI's default view with its
 * default look to a second PPM, the bytes of `voxtrace --vox FILE --width
 * 320 --height 180 --format ppm`.
 *
 *   cc examples/terrain.c -Iinclude -L../../target/release -lvoxtrace_capi -o terrain
 *   LD_LIBRARY_PATH=../../target/release ./terrain terrain.ppm [model.vox model.ppm]
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

/* Writes `width` x `height` RGBA pixels to `path` as a binary PPM. */
static int write_ppm(const char *path, const unsigned char *rgba, unsigned width, unsigned height) {
    FILE *file = fopen(path, "wb");
    if (file == NULL) return 1;
    fprintf(file, "P6\n%u %u 255\n", width, height);
    for (size_t i = 0; i < (size_t)width * height * 4; i += 4) fwrite(rgba + i, 1, 3, file);
    return fclose(file) != 0;
}

/* Reads the whole file at `path` into a new buffer; its length in `*len`. */
static unsigned char *read_file(const char *path, size_t *len) {
    FILE *file = fopen(path, "rb");
    if (file == NULL) return NULL;
    fseek(file, 0, SEEK_END);
    long size = ftell(file);
    fseek(file, 0, SEEK_SET);
    unsigned char *bytes = size > 0 ? malloc((size_t)size) : NULL;
    if (bytes != NULL && fread(bytes, 1, (size_t)size, file) != (size_t)size) {
        free(bytes);
        bytes = NULL;
    }
    fclose(file);
    *len = (size_t)size;
    return bytes;
}

int main(int argc, char **argv) {
    const char *out = argc > 1 ? argv[1] : "terrain.ppm";
    VtScene *scene = NULL;
    if (vt_scene_terrain(100, 1, VT_BACKEND_OCTREE, &scene) != VT_STATUS_OK) return fail("terrain");
    VtView view = {.width = 320, .height = 180, .aim = VT_AIM_POSITION,
                   .position = {90.0f, 90.0f, 90.0f}, .lookat = {0.0f, 0.0f, 0.0f}};
    size_t len = (size_t)view.width * view.height * 4;
    unsigned char *rgba = malloc(len);
    if (rgba == NULL) return 1;
    if (vt_render(scene, &view, NULL, 0, rgba, len) != VT_STATUS_OK) return fail("render");
    /* A refused call: the buffer is one byte short. */
    if (vt_render(scene, &view, NULL, 1, rgba, len - 1) != VT_STATUS_INVALID_ARGUMENT) return 1;
    vt_scene_free(scene);
    if (write_ppm(out, rgba, view.width, view.height) != 0) return 1;
    if (argc > 3) {
        size_t size = 0;
        unsigned char *file = read_file(argv[2], &size);
        if (file == NULL) return 1;
        if (vt_scene_vox(file, size, 0, VT_BACKEND_OCTREE, &scene) != VT_STATUS_OK) return fail("vox");
        free(file);
        if (vt_default_view(scene, 320, 180, &view) != VT_STATUS_OK) return fail("view");
        if (vt_render(scene, &view, NULL, 0, rgba, len) != VT_STATUS_OK) return fail("render");
        vt_scene_free(scene);
        if (write_ppm(argv[3], rgba, view.width, view.height) != 0) return 1;
    }
    free(rgba);
    return 0;
}
