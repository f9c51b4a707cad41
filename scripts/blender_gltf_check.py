"""Independent check of an exported .glb with Blender's own glTF importer.

Usage:
  blender -b --factory-startup --python scripts/blender_gltf_check.py -- FILE.glb [FRAME_A FRAME_B] [--raw]

Prints one JSON line (prefixed "GLTFCHECK ") on stdout:
  file, blender (version), fps (scene fps; --factory-startup gives 24), import_s (seconds spent in
  bpy.ops.import_scene.gltf), bones (joint count of the armature(s), 0 if none), shape_keys (shape
  keys on the mesh objects, "Basis" not counted), meshes [{name, verts, skinned, shape_keys}],
  actions [{name, id_root (OBJECT = bones, KEY = shape keys), frame_range, length_s}],
  vertex {mesh, index, frames, times_s, pos_blender, pos_gltf}.
The vertex is the one of the largest mesh (most vertices) that moves the most between FRAME_A and
FRAME_B (default: first frame of the action and the middle frame), evaluated through the depsgraph
(shape keys, then the armature modifier, then the object's world matrix). index is Blender's vertex
index; scripts/blender_gltf_compare.py maps it back to the glTF vertex. Positions are in metres:
pos_blender in Blender's +Z up world, pos_gltf the same converted back to glTF +Y up
(gltf = (x, z, -y) of Blender). The importer keys glTF time t at frame t * fps, so times_s = frame / fps.
slider_widened: shape keys whose slider range had to be widened to the animated weight range.
The Blender 3.4 importer sets the range from the first key only (min(coords[1:2]) in
gltf2_blender_animation_weight.py), so Blender clamps e.g. negative corrective weights to it;
this script widens the ranges after import unless --raw is given (then it reports what a plain
import shows).
Exits 1 with a message on stderr if the import fails.
"""
import json, sys, time
import bpy
import numpy as np

# Debian 12's Blender 3.4.1 importer uses np.bool (gltf2_blender_mesh.py:612), which numpy 1.24
# removed: without this alias every mesh import fails with AttributeError.
if 'bool' not in vars(np):  # (hasattr would trip numpy's deprecation warning)
    np.bool = bool

argv = sys.argv[sys.argv.index('--') + 1:] if '--' in sys.argv else []
raw = '--raw' in argv
argv = [a for a in argv if a != '--raw']
if not argv:
    sys.stderr.write(__doc__); sys.exit(2)
path = argv[0]

bpy.ops.wm.read_factory_settings(use_empty=True)  # drop the default cube, camera and light
t0 = time.perf_counter()
try:
    res = bpy.ops.import_scene.gltf(filepath=path)
except Exception as e:  # the operator raises RuntimeError on a bad file
    res = ' | '.join(str(e).strip().splitlines()[-2:])  # the last lines name the actual error
import_s = time.perf_counter() - t0
if res != {'FINISHED'}:
    sys.stderr.write(f"blender_gltf_check: import of {path} failed: {res}\n"); sys.exit(1)

scene = bpy.context.scene
fps = scene.render.fps / scene.render.fps_base
arms = [o for o in scene.objects if o.type == 'ARMATURE']
mesh_objs = [o for o in scene.objects if o.type == 'MESH']
if not mesh_objs:
    sys.stderr.write(f"blender_gltf_check: {path} has no mesh\n"); sys.exit(1)

slider_widened = 0  # undo the importer's slider clamp (see the top)
for o in mesh_objs:
    sk = o.data.shape_keys
    act = sk and sk.animation_data and sk.animation_data.action
    for fc in (act.fcurves if act else []):
        if raw or not fc.data_path.endswith('.value'): continue
        kb = sk.path_resolve(fc.data_path.rsplit('.', 1)[0])
        vals = [k.co[1] for k in fc.keyframe_points]
        if min(vals) < kb.slider_min or max(vals) > kb.slider_max:
            kb.slider_min = min(kb.slider_min, min(vals)); kb.slider_max = max(kb.slider_max, max(vals))
            slider_widened += 1

def n_keys(o):  # shape keys without the "Basis" reference key
    k = o.data.shape_keys
    return len(k.key_blocks) - 1 if k else 0

meshes = [{'name': o.name, 'verts': len(o.data.vertices), 'shape_keys': n_keys(o),
           'skinned': any(m.type == 'ARMATURE' for m in o.modifiers)} for o in mesh_objs]
actions = [{'name': a.name, 'id_root': a.id_root, 'frame_range': list(a.frame_range),
            'length_s': (a.frame_range[1] - a.frame_range[0]) / fps}
           for a in bpy.data.actions if a.users]

# frames: given, or the first and the middle frame of the (union of the) actions
if len(argv) >= 3:
    fa, fb = float(argv[1]), float(argv[2])
elif actions:
    lo = min(a['frame_range'][0] for a in actions); hi = max(a['frame_range'][1] for a in actions)
    fa, fb = lo, float(round((lo + hi) / 2))
else:
    fa = fb = float(scene.frame_current)

obj = max(mesh_objs, key=lambda o: len(o.data.vertices))

def world_verts(frame):
    """Evaluated world positions (N, 3) of obj's vertices at a (possibly fractional) frame."""
    scene.frame_set(int(np.floor(frame)), subframe=float(frame - np.floor(frame)))
    dg = bpy.context.evaluated_depsgraph_get()
    ob = obj.evaluated_get(dg)
    me = ob.to_mesh()
    co = np.empty(len(me.vertices) * 3); me.vertices.foreach_get('co', co)
    ob.to_mesh_clear()
    M = np.array(ob.matrix_world)
    return co.reshape(-1, 3) @ M[:3, :3].T + M[:3, 3]

A, B = world_verts(fa), world_verts(fb)
i = int(np.argmax(np.linalg.norm(B - A, axis=1)))
to_gltf = lambda p: [float(p[0]), float(p[2]), float(-p[1])]
out = {'file': path, 'blender': bpy.app.version_string, 'fps': fps, 'import_s': round(import_s, 3),
       'bones': sum(len(a.data.bones) for a in arms), 'shape_keys': sum(m['shape_keys'] for m in meshes),
       'slider_widened': slider_widened, 'raw': raw,
       'meshes': meshes, 'actions': actions,
       'vertex': {'mesh': obj.name, 'index': i, 'frames': [fa, fb], 'times_s': [fa / fps, fb / fps],
                  'pos_blender': [A[i].tolist(), B[i].tolist()], 'pos_gltf': [to_gltf(A[i]), to_gltf(B[i])]}}
print('GLTFCHECK ' + json.dumps(out), flush=True)
