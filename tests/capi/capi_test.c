/* The C API (wirerig.h) from C: loads a built rig asset (argv[1], made by `wirerig build --clips`
 * from samples/human/human_wave.scene.json), its clip (argv[2]) and a clip of another rig
 * (argv[3], the octopus's; argv[4] is the octopus's rig, whose mantle is rigid), evaluates frames
 * into interleaved float buffers and checks the API's contract: errors with statuses and messages,
 * outputs untouched on failure, determinism, a bent joint moving only its side, the source and
 * welded orders agreeing, a clip playing and looping, a clip of another rig refused, rotated
 * normals. Prints a line per failed check; exits 0 only when every check holds. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "wirerig/wirerig.h"

static int failures = 0;
#define CHECK(condition)                                                            \
  do {                                                                              \
    if (!(condition)) {                                                             \
      fprintf(stderr, "%s:%d: check failed: %s\n", __FILE__, __LINE__, #condition); \
      ++failures;                                                                   \
    }                                                                               \
  } while (0)

static float* Evaluate(wr_context* context, wr_vertex_order order, uint32_t vertices) {
  /* Interleaved position + normal, stride 6 floats. */
  float* buffer = malloc(sizeof(float) * 6 * vertices);
  wr_status s = wr_context_evaluate(context, order, buffer, 6, buffer + 3, 6, 6 * (size_t)vertices);
  CHECK(s == WR_OK);
  if (s != WR_OK) fprintf(stderr, "  %s\n", wr_last_error());
  return buffer;
}

int main(int argc, char** argv) {
  if (argc != 5) {
    fprintf(stderr, "usage: %s RIG.wrig CLIP.wclip OTHER_RIGS_CLIP.wclip OTHER_RIG.wrig\n",
            argv[0]);
    return 2;
  }
  wr_rig* rig = NULL;
  /* A missing file and garbage bytes are refused with a message and no rig. */
  CHECK(wr_rig_load_file("/nonexistent/rig.wrig", &rig) == WR_IO_ERROR && rig == NULL);
  CHECK(strstr(wr_last_error(), "/nonexistent/rig.wrig: no such file") != NULL);
  CHECK(wr_rig_load_file("/", &rig) == WR_IO_ERROR && rig == NULL);
  CHECK(strstr(wr_last_error(), "not a regular file") != NULL);
  const char garbage[40] = "WRIG and then nothing that makes sense";
  CHECK(wr_rig_load_memory(garbage, sizeof garbage, &rig) == WR_BAD_ASSET && rig == NULL);
  CHECK(strstr(wr_last_error(), "rig asset") != NULL);
  CHECK(wr_rig_load_memory(NULL, 5, &rig) == WR_INVALID_ARGUMENT && rig == NULL);
  /* No bytes at all (an empty file) is a bad asset, not a missing argument. */
  CHECK(wr_rig_load_memory(NULL, 0, &rig) == WR_BAD_ASSET && rig == NULL);
  FILE* empty = fopen("capi_test_empty.wrig", "wb");
  CHECK(empty != NULL);
  if (empty) fclose(empty);
  CHECK(wr_rig_load_file("capi_test_empty.wrig", &rig) == WR_BAD_ASSET && rig == NULL);
  CHECK(strstr(wr_last_error(), "capi_test_empty.wrig: rig asset") != NULL);
  remove("capi_test_empty.wrig");

  if (wr_rig_load_file(argv[1], &rig) != WR_OK) {
    fprintf(stderr, "cannot load %s: %s\n", argv[1], wr_last_error());
    return 1;
  }
  const uint32_t parts = wr_rig_part_count(rig);
  const uint32_t source = wr_rig_vertex_count(rig, WR_ORDER_SOURCE);
  const uint32_t welded = wr_rig_vertex_count(rig, WR_ORDER_WELDED);
  const uint32_t triangles = wr_rig_triangle_count(rig);
  printf("rig: %u parts, %u source vertices, %u welded, %u triangles\n", parts, source, welded,
         triangles);
  CHECK(parts >= 2 && source >= welded && welded > 0 && triangles > 0);
  const int32_t forearm = wr_rig_find_part(rig, "forearm_l");
  CHECK(forearm > 0);
  CHECK(wr_rig_find_part(rig, "no such part") == -1);
  CHECK(wr_rig_part_parent(rig, 0) == -1);
  CHECK(strcmp(wr_rig_part_name(rig, (uint32_t)forearm), "forearm_l") == 0);
  CHECK(wr_rig_part_name(rig, parts) == NULL);

  uint32_t* indices = malloc(sizeof(uint32_t) * 3 * triangles);
  CHECK(wr_rig_welded_triangles(rig, indices, 3) == WR_INVALID_ARGUMENT);
  CHECK(wr_rig_welded_triangles(rig, indices, 3 * (size_t)triangles) == WR_OK);
  for (uint32_t i = 0; i < 3 * triangles; ++i) CHECK(indices[i] < welded);

  wr_context* context = NULL;
  CHECK(wr_context_create(rig, &context) == WR_OK);
  float* rest = Evaluate(context, WR_ORDER_WELDED, welded);
  float* rest_again = Evaluate(context, WR_ORDER_WELDED, welded);
  CHECK(memcmp(rest, rest_again, sizeof(float) * 6 * welded) == 0);

  /* Bad arguments: refused with a message, the buffer untouched. */
  CHECK(wr_context_set_joint_angles(context, parts, 10, 0, 0) == WR_INVALID_ARGUMENT);
  CHECK(strstr(wr_last_error(), "out of range") != NULL);
  CHECK(wr_context_set_joint_angles(context, 0, 10, 0, 0) == WR_INVALID_ARGUMENT);
  CHECK(wr_context_set_joint_angles(context, 1, NAN, 0, 0) == WR_INVALID_ARGUMENT);
  const float at_bad[1] = {1.5f}, force[3] = {0, 5, 0};
  CHECK(wr_context_set_point_loads(context, 1, at_bad, force, 1) == WR_INVALID_ARGUMENT);
  /* A translation beyond 1e6 m (1e36 gave NaN positions with WR_OK). */
  const float identity[4] = {0, 0, 0, 1}, far[3] = {1e7f, 0, 0};
  CHECK(wr_context_set_part_transform(context, 0, identity, far) == WR_INVALID_ARGUMENT);
  CHECK(strstr(wr_last_error(), "within 1e6 m") != NULL);
  float small[6] = {42, 42, 42, 42, 42, 42};
  CHECK(wr_context_evaluate(context, WR_ORDER_WELDED, small, 3, NULL, 3, 6) == WR_INVALID_ARGUMENT);
  CHECK(strstr(wr_last_error(), "float_positions") != NULL);
  for (int i = 0; i < 6; ++i) CHECK(small[i] == 42.0f);

  /* The left elbow bent by 90 degrees: the left hand moves, the other side stays exactly. */
  CHECK(wr_context_set_joint_angles(context, (uint32_t)forearm, 90, 0, 0) == WR_OK);
  float* bent = Evaluate(context, WR_ORDER_WELDED, welded);
  uint32_t moved = 0, right_side_moved = 0;
  float largest = 0;
  for (uint32_t v = 0; v < welded; ++v) {
    const float* a = rest + 6 * v;
    const float* b = bent + 6 * v;
    const float d = sqrtf((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                          (a[2] - b[2]) * (a[2] - b[2]));
    CHECK(isfinite(b[0]) && isfinite(b[3]));
    if (d > 1e-6f) ++moved;
    if (d > largest) largest = d;
    /* The human faces +Z with its left side at +X: the right arm (x < -0.15) must not move. */
    if (a[0] < -0.15f && d != 0.0f) ++right_side_moved;
  }
  printf("elbow at 90 degrees: %u vertices moved, the farthest by %.3f m\n", moved, largest);
  CHECK(moved > 100 && largest > 0.1f && largest < 1.0f && right_side_moved == 0);

  /* Rotated normals: the same positions, unit normals; a mode outside the enum refused. */
  CHECK(wr_context_set_normal_mode(context, (wr_normal_mode)7) == WR_INVALID_ARGUMENT);
  CHECK(wr_context_set_normal_mode(context, WR_NORMALS_ROTATED) == WR_OK);
  float* rotated = Evaluate(context, WR_ORDER_WELDED, welded);
  for (uint32_t v = 0; v < welded; ++v) {
    const float* n = rotated + 6 * v + 3;
    CHECK(memcmp(rotated + 6 * v, bent + 6 * v, sizeof(float) * 3) == 0);
    CHECK(fabsf(sqrtf(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]) - 1.0f) < 1e-5f);
  }
  CHECK(wr_context_set_normal_mode(context, WR_NORMALS_FROM_TRIANGLES) == WR_OK);
  free(rotated);

  /* The source order holds copies of the welded vertices. */
  float* bent_source = Evaluate(context, WR_ORDER_SOURCE, source);
  uint32_t matched = 0;
  for (uint32_t i = 0; i < source; ++i)
    for (uint32_t v = 0; v < welded && v < 64; ++v)
      if (memcmp(bent_source + 6 * i, bent + 6 * v, sizeof(float) * 3) == 0) ++matched;
  CHECK(matched > 0);

  /* Reset brings back the rest frame exactly. */
  wr_context_reset(context);
  float* back = Evaluate(context, WR_ORDER_WELDED, welded);
  CHECK(memcmp(back, rest, sizeof(float) * 6 * welded) == 0);

  /* The rig's own clip plays: frames move, the time loops, joint angles add on top. */
  wr_clip* clip = NULL;
  wr_clip* other = NULL;
  CHECK(wr_clip_load_file(argv[1], &clip) == WR_BAD_ASSET && clip == NULL); /* a .wrig */
  CHECK(strstr(wr_last_error(), "clip asset") != NULL);
  if (wr_clip_load_file(argv[2], &clip) != WR_OK || wr_clip_load_file(argv[3], &other) != WR_OK) {
    fprintf(stderr, "cannot load the clips: %s\n", wr_last_error());
    return 1;
  }
  const double duration = wr_clip_duration(clip);
  printf("clip \"%s\": %.2f s\n", wr_clip_name(clip), duration);
  CHECK(duration > 0.0);
  CHECK(wr_context_set_clip(context, other, 0.0) == WR_INVALID_ARGUMENT);
  CHECK(strstr(wr_last_error(), "does not fit this rig") != NULL);
  CHECK(wr_context_set_clip(context, clip, 0.0) == WR_OK);
  float* start = Evaluate(context, WR_ORDER_WELDED, welded);
  CHECK(wr_context_set_clip(context, clip, 0.5 * duration) == WR_OK);
  float* middle = Evaluate(context, WR_ORDER_WELDED, welded);
  CHECK(memcmp(start, middle, sizeof(float) * 6 * welded) != 0);
  CHECK(wr_context_set_clip(context, clip, 0.5 * duration) == WR_OK);
  float* middle_again = Evaluate(context, WR_ORDER_WELDED, welded);
  CHECK(memcmp(middle, middle_again, sizeof(float) * 6 * welded) == 0);
  CHECK(wr_context_set_clip(context, clip, NAN) == WR_INVALID_ARGUMENT);
  CHECK(wr_context_set_clip(context, NULL, 0.0) == WR_OK);
  float* unplayed = Evaluate(context, WR_ORDER_WELDED, welded);
  CHECK(memcmp(unplayed, rest, sizeof(float) * 6 * welded) == 0);

  free(start);
  free(middle);
  free(middle_again);
  free(unplayed);
  wr_clip_free(clip);
  wr_clip_free(other);
  free(indices);
  free(rest);
  free(rest_again);
  free(bent);
  free(bent_source);
  free(back);
  wr_context_free(context);
  wr_rig_free(rig);

  /* Loads on a rigid part (the octopus's mantle) are refused: they would move nothing. */
  wr_rig* octopus = NULL;
  wr_context* octopus_context = NULL;
  CHECK(wr_rig_load_file(argv[4], &octopus) == WR_OK);
  if (octopus != NULL && wr_context_create(octopus, &octopus_context) == WR_OK) {
    const int32_t mantle = wr_rig_find_part(octopus, "mantle");
    CHECK(mantle == 0);
    const float at[1] = {1.0f}, push[3] = {0, 1000, 1000};
    CHECK(wr_context_set_point_loads(octopus_context, 0, at, push, 1) == WR_INVALID_ARGUMENT);
    CHECK(strstr(wr_last_error(), "is rigid") != NULL);
    CHECK(wr_context_set_point_loads(octopus_context, 1, at, push, 1) == WR_OK); /* an arm */
  }
  wr_context_free(octopus_context);
  wr_rig_free(octopus);
  if (failures == 0) printf("all C API checks hold\n");
  return failures == 0 ? 0 : 1;
}
