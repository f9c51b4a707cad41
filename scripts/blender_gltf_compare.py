#!/usr/bin/python3
"""Compare the vertex position Blender reports (scripts/blender_gltf_check.py) with an independent
numpy evaluation of the same .glb (glTF rules: morph weights, then skin = sum w * joint world * IBM;
the node transform of a skinned mesh is ignored).

Usage:
  blender -b --factory-startup --python scripts/blender_gltf_check.py -- FILE.glb > check.txt
  /usr/bin/python3 scripts/blender_gltf_compare.py FILE.glb check.txt   (or '-' for stdin)

Prints one JSON line: prim and glTF vertex index, glTF times (s), pos_ref (numpy, glTF +Y up, m),
pos_blender (Blender's, converted back to +Y up, m), diff_m (distance per frame, m) and
morph_m (length of the morph-target offset at each frame, m, to show the correctives mattered).
Blender's vertex order: for each primitive in order, the sorted unique vertices its indices use
(importer option merge_vertices off, the default).
"""
import json, os, sys
import numpy as np
# The glTF readers of the shared tools (meshquality.py, skin_vs_morph.py): WIRERIG_SHARED_TOOLS,
# or ../shared/tools beside the repository.
sys.path.insert(0, os.environ.get('WIRERIG_SHARED_TOOLS', os.path.join(
    os.path.dirname(os.path.abspath(__file__)), '..', '..', 'shared', 'tools')))
from meshquality import load, accessor
from skin_vs_morph import sample, world_mats

path, check = sys.argv[1], sys.argv[2]
lines = (sys.stdin if check == '-' else open(check)).read().splitlines()
rep = json.loads(next(l for l in lines if l.startswith('GLTFCHECK '))[len('GLTFCHECK '):])
v = rep['vertex']
j, b = load(path)

# the largest mesh node (most POSITION entries over its primitives), as the Blender script picks
def n_verts(mi):
    prims = j['meshes'][mi]['primitives']
    return sum(len(np.unique(accessor(j, b, p['indices']))) if 'indices' in p
               else j['accessors'][p['attributes']['POSITION']]['count'] for p in prims)
node_i = max((i for i, n in enumerate(j['nodes']) if 'mesh' in n), key=lambda i: n_verts(j['nodes'][i]['mesh']))
node = j['nodes'][node_i]; mesh = j['meshes'][node['mesh']]

# Blender vertex index -> (primitive, glTF vertex)
k = v['index']
for pi, prim in enumerate(mesh['primitives']):
    used = (np.unique(accessor(j, b, prim['indices']).astype(np.int64)) if 'indices' in prim
            else np.arange(j['accessors'][prim['attributes']['POSITION']]['count']))
    if k < len(used): gv = int(used[k]); break
    k -= len(used)

def attr(name):
    return accessor(j, b, prim['attributes'][name])[gv] if name in prim['attributes'] else None

anim = (j.get('animations') or [{}])[0]
ref, morph = [], []
for t in v['times_s']:
    over = {}
    for ch in anim.get('channels', []):
        over.setdefault(ch['target']['node'], {})[ch['target']['path']] = sample(j, b, anim['samplers'][ch['sampler']], t)
    W = world_mats(j, over)
    P = attr('POSITION').copy(); d = np.zeros(3)
    w = over.get(node_i, {}).get('weights', mesh.get('weights', [0] * len(prim.get('targets', []))))
    for wi, tg in zip(w, prim.get('targets', [])):
        if wi: d += wi * accessor(j, b, tg['POSITION'])[gv]
    P = np.r_[P + d, 1.0]
    if 'skin' in node:
        sk = j['skins'][node['skin']]
        IB = accessor(j, b, sk['inverseBindMatrices']).reshape(-1, 4, 4).transpose(0, 2, 1)
        J, Wt = [attr('JOINTS_0').astype(int)], [attr('WEIGHTS_0')]
        if 'JOINTS_1' in prim['attributes']: J.append(attr('JOINTS_1').astype(int)); Wt.append(attr('WEIGHTS_1'))
        J, Wt = np.concatenate(J), np.concatenate(Wt); Wt = Wt / Wt.sum()
        x = sum(wt * (W(sk['joints'][jn]) @ IB[jn] @ P) for jn, wt in zip(J, Wt) if wt)
    else:
        x = W(node_i) @ P
    ref.append(x[:3]); morph.append(float(np.linalg.norm(d)))

bl = np.array(v['pos_gltf'])
print(json.dumps({'file': path, 'prim': pi, 'gltf_vertex': gv, 'times_s': v['times_s'],
                  'pos_ref': [r.tolist() for r in ref], 'pos_blender': bl.tolist(),
                  'diff_m': [float(np.linalg.norm(r - q)) for r, q in zip(ref, bl)], 'morph_m': morph}))
