/* wirerig.h: the C API of the wirerig runtime, for engines and language bindings (C#, Rust,
 * Python, Lua, ...). It loads a built rig asset (.wrig, made by `wirerig build`), poses its
 * joints, sets spine loads and evaluates the deformed mesh into the caller's float vertex
 * buffers. It links only the runtime (Eigen inside; no Assimp, CGAL, JSON or glTF).
 *
 * Conventions: SI units (metres, newtons), glTF axes (right-handed, +Y up), angles of joints in
 * degrees about the joint's own axes (X the hinge or first bend, Y the second bend, Z the twist
 * along the bone; clamped to the joint's type and limits), quaternions as (x, y, z, w).
 *
 * Errors: every function that can fail returns a wr_status; WR_OK is 0. On failure the output
 * arguments are untouched and wr_last_error() returns a message for the calling thread naming the
 * argument or the asset's field at fault. No C++ exception crosses this API.
 *
 * Threads: a wr_rig and a wr_clip are immutable once loaded and may be shared by any number of
 * threads; each thread evaluates through its own wr_context. wr_context_evaluate allocates
 * nothing. A rig and the clips set on a context must outlive the context.
 */
#ifndef WIRERIG_WIRERIG_H_
#define WIRERIG_WIRERIG_H_

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef enum wr_status {
  WR_OK = 0,
  WR_INVALID_ARGUMENT = 1, /* a null pointer, an index out of range, a non-finite number */
  WR_BAD_ASSET = 2,        /* the bytes are not a valid rig asset (wrong magic, corrupt, ...) */
  WR_IO_ERROR = 3,         /* the file cannot be read */
  WR_OUT_OF_MEMORY = 4
} wr_status;

/* The vertex order of evaluated buffers: the source asset's (as the engine imported the mesh,
 * with vertices split at seams), or the rig's welded one (one vertex per position). */
/* Enumerations taken as arguments end in a 32-bit sentinel (as Vulkan's do), so that any int a
 * caller passes is a value of the type and is refused with WR_INVALID_ARGUMENT when it names
 * no enumerator. */
typedef enum wr_vertex_order {
  WR_ORDER_SOURCE = 0,
  WR_ORDER_WELDED = 1,
  WR_ORDER_MAX_ENUM = 0x7FFFFFFF
} wr_vertex_order;

typedef struct wr_rig wr_rig;
typedef struct wr_clip wr_clip;
typedef struct wr_context wr_context;

/* The message of the calling thread's last failure ("" if none). Valid until its next call. */
const char* wr_last_error(void);

/* Loads a rig asset from memory (the bytes are copied as needed; bytes may be null when size is
   0, which is refused as a bad asset) or from a file. */
wr_status wr_rig_load_memory(const void* bytes, size_t size, wr_rig** out);
wr_status wr_rig_load_file(const char* path, wr_rig** out);
void wr_rig_free(wr_rig* rig); /* null is allowed */

uint32_t wr_rig_part_count(const wr_rig* rig);
/* The part's name, or null when part is out of range. Owned by the rig. */
const char* wr_rig_part_name(const wr_rig* rig, uint32_t part);
/* The part's index, or -1 when no part has this name. */
int32_t wr_rig_find_part(const wr_rig* rig, const char* name);
/* The part's parent, or -1 for a root or an index out of range. */
int32_t wr_rig_part_parent(const wr_rig* rig, uint32_t part);
/* Output vertices in an order (0 when the order is unknown). */
uint32_t wr_rig_vertex_count(const wr_rig* rig, wr_vertex_order order);
uint32_t wr_rig_triangle_count(const wr_rig* rig);
/* Writes 3 x wr_rig_triangle_count indices into WR_ORDER_WELDED vertices. */
wr_status wr_rig_welded_triangles(const wr_rig* rig, uint32_t* indices, size_t capacity);

/* Loads a clip asset (.wclip, made by `wirerig build --clips`): a clip sampled for the runtime
 * (poses, joint angles, dynamics and loads already resolved, the wires' inertial motion
 * recorded). Immutable; shareable. */
wr_status wr_clip_load_memory(const void* bytes, size_t size, wr_clip** out);
wr_status wr_clip_load_file(const char* path, wr_clip** out);
void wr_clip_free(wr_clip* clip); /* null is allowed */
const char* wr_clip_name(const wr_clip* clip);
double wr_clip_duration(const wr_clip* clip); /* s */

/* A per-thread evaluation context: every part at rest, no loads, no clip. */
wr_status wr_context_create(const wr_rig* rig, wr_context** out);
void wr_context_free(wr_context* context); /* null is allowed */
/* Every part back to rest, every load removed. */
void wr_context_reset(wr_context* context);
/* A part's joint angles in degrees (clamped to the joint's type and limits); refused on a root. */
wr_status wr_context_set_joint_angles(wr_context* context, uint32_t part, float x_degrees,
                                      float y_degrees, float z_degrees);
/* A part's rigid pose: rotation (x, y, z, w; normalised here) about its spine's root point,
 * then translation in metres (each component within 1e6), world axes; the part then follows
 * its parent's motion, so poses compose down the chain (a child's translation adds to its
 * parent's). Joint angles set later compose after it. Evaluation is in float, in world space:
 * its precision falls with the distance from the origin (about 0.03 mm at 100 m, 0.2 mm and
 * normals degrees off at 1 km), so keep a character near the origin and place it with the
 * engine's model matrix. */
wr_status wr_context_set_part_transform(wr_context* context, uint32_t part,
                                        const float rotation_xyzw[4], const float translation[3]);
/* Bending point loads on a part's spine (deformable parts only: refused on a rigid one, where
 * they would move nothing): `count` loads at spine parameters
 * at[i] in [0, 1] with forces forces[3 i .. 3 i + 2] in newtons, in the spine's local axes (x
 * along the rest normal, y along the rest binormal). Replaces the part's previous loads; count
 * 0 removes them. Allocates (call it when loads change, not per vertex). */
wr_status wr_context_set_point_loads(wr_context* context, uint32_t part, const float* at,
                                     const float* forces, uint32_t count);
/* Plays `clip` (null: none) at playback time `time` in s (looping as the clip says): poses and
 * loads then come from the clip, with joint angles set above turning on top; part transforms
 * and point loads set above apply only while no clip is set. Refused when the clip was made for
 * a rig with another number of parts, or names profiles or wires this rig does not have (a clip
 * does not otherwise identify its rig: play a rig's own clips). Allocates when the clip differs
 * from the context's previous one, never when only the time changes. */
wr_status wr_context_set_clip(wr_context* context, const wr_clip* clip, double time);
/* How wr_context_evaluate makes normals: from the deformed triangles (the default), or each
 * vertex's rest normal turned with the frame it rides on (the vertices on joints' skin bridges
 * still from their triangles): the same positions, exact under rigid motion, within a degree
 * for most vertices but tens of degrees off on fingers and toes when the flesh stretches; no
 * faster where most vertices lie on bridges (the human's). Kept by wr_context_reset. */
typedef enum wr_normal_mode {
  WR_NORMALS_FROM_TRIANGLES = 0,
  WR_NORMALS_ROTATED = 1,
  WR_NORMALS_MAX_ENUM = 0x7FFFFFFF
} wr_normal_mode;
wr_status wr_context_set_normal_mode(wr_context* context, wr_normal_mode mode);
/* Evaluates the pose into float buffers: vertex i's position at positions[i * position_stride
 * .. + 2] and its unit normal likewise (normals may be null). Strides in floats, at least 3.
 * From each pointer it writes within the first (n - 1) * stride + 3 floats, and `capacity`
 * (floats available at each pointer) must cover that: an interleaved buffer of n vertices
 * (positions at p, normals at p + 3, stride 6) passes 6 n. Writes nothing on failure. */
wr_status wr_context_evaluate(wr_context* context, wr_vertex_order order, float* positions,
                              size_t position_stride, float* normals, size_t normal_stride,
                              size_t capacity);

#ifdef __cplusplus
}
#endif

#endif /* WIRERIG_WIRERIG_H_ */
