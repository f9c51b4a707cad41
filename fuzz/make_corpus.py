#!/usr/bin/env python3
"""Writes the seed corpora of the fuzz targets (fuzz/corpus/<target>/) and the JSON dictionary
(fuzz/json.dict) from the samples, Assimp's test models and a small two-part rig built with the
wirerig command. Run from anywhere:

    fuzz/make_corpus.py --wirerig build/cli/wirerig [--assimp-models /usr/share/assimp/models]

Each corpus is rewritten from scratch; findings (inputs that crashed a fuzzer and were fixed,
named finding-*) are kept. Seeds stay small (the whole corpus under 1 MB).
"""
import argparse
import json
import math
import pathlib
import shutil
import subprocess
import tempfile

FUZZ = pathlib.Path(__file__).resolve().parent
REPO = FUZZ.parent
CORPUS = FUZZ / "corpus"

# The mesh fuzzer's first byte picks the extension: keep in step with kExtensions in
# mesh_import_fuzzer.cpp.
EXTENSIONS = ["off", "ply", "obj", "stl", "dae", "x", "gltf", "glb", "fbx", "3ds", "ac", "lwo",
              "ms3d", "md2", "nff", "ase", "smd", "b3d", "xgl", "bvh", "blend", "zae", "raw", "ter"]

MESH_SEEDS = [  # (file under the Assimp models folder, extension)
    ("OFF/Cube.off", "off"),
    ("PLY/cube.ply", "ply"),
    ("PLY/cube_binary.ply", "ply"),
    ("OBJ/box.obj", "obj"),
    ("OBJ/cube_usemtl.obj", "obj"),
    ("STL/triangle_with_two_solids.stl", "stl"),
    ("Collada/cube_emptyTags.dae", "dae"),
    ("X/test_cube_text.x", "x"),
    ("X/test_cube_compressed.x", "x"),
    ("glTF2/BoxBadNormals-glTF-Binary/BoxBadNormals.glb", "glb"),
    ("3DS/cube_with_diffuse_texture.3DS", "3ds"),
    ("AC/closedLine.ac", "ac"),  # sample_subdiv.ac subdivides to 123k vertices: too slow
    ("LWO/LWO2/boxuv.lwo", "lwo"),
    ("NFF/NFF/cone.nff", "nff"),
    ("SMD/triangle.smd", "smd"),
    ("XGL/sample_official.xgl", "xgl"),
    ("RAW/WithColor.raw", "raw"),
]

# Wire problems beyond the worked sample: each boundary family, series mode, strips, presets.
WIRE_SEEDS = {
    "doc_example.json": {
        "length": 2.0, "material": {"E": 2.0e9, "nu": 0.3, "density": 1000},
        "section": {"A": 1e-4, "I": 1e-8}, "samples": 101,
        "bending": {"bc": "clamped", "mode": "exact", "terms": 20, "ends": [[0, 0, 0], [0, 0, 0]],
                    "tip_force": [0, 0, 0], "point_loads": [{"at": 0.3, "force": [0, -10, 0]}],
                    "line_loads": [{"from": 0.2, "to": 0.6, "force_per_length": [0, -5, 0]}]},
        "axial": {"fixed_at": 0.5, "point_loads": [{"at": 0.8, "force": 10.0}],
                  "line_loads": [{"from": 0.6, "to": 1.0, "force_per_length": 2.0}]}},
    "series_simply_supported.json": {
        "length": 1.0, "material": "steel", "section": {"strip": {"b": 0.05, "h": 0.004}},
        "samples": 21, "bending": {"bc": "simply_supported", "mode": "series", "terms": 40,
                                   "ends": [[0, 0.01, 0], [0, -0.01, 0]],
                                   "point_loads": [{"at": 0.5, "force": [0, -100, 5]}]}},
    "guided_cantilever.json": {
        "length": 0.3, "material": "rubber", "section": {"tube": {"r": 0.01, "h": 0.003}},
        "samples": 5, "bending": {"bc": "cantilever_guided", "tip_force": [0.2, 0, 0]}},
    "axial_only.json": {
        "length": 3.0, "material": {"E": 7e10, "nu": 0.33}, "section": {"A": 2e-4, "I": 1e-9},
        "samples": 7, "axial": {"fixed_at": 1.0, "point_loads": [{"at": 0.0, "force": -50}]}},
}

BVH_SEED = """HIERARCHY
ROOT Hips
{
  OFFSET 0 0 0
  CHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation
  JOINT Spine
  {
    OFFSET 0 10 0
    CHANNELS 3 Zrotation Yrotation Xrotation
    End Site
    {
      OFFSET 0 8 0
    }
  }
  JOINT Leg
  {
    OFFSET 2 -1 0
    CHANNELS 3 Xrotation Yrotation Zrotation
    End Site
    {
      OFFSET 0 -9 0
    }
  }
}
MOTION
Frames: 3
Frame Time: 0.0333333
0 0 0 0 0 0 0 0 0 0 0 0
1 2 3 10 20 30 5 6 7 -10 0 4
2 4 6 20 40 60 10 12 14 -20 0 8
"""

# A procedural cylinder 1 m tall rigged as "base" and "arm" (fuzz/fuzz_rigs.h rigs the same).
PARTS = [
    {"name": "base", "central_curve": [[0, 1, 0], [0, 0.5, 0]], "profile_count": 3,
     "points_per_profile": 8},
    {"name": "arm", "parent": "base", "central_curve": [[0, 0.5, 0], [0, 0, 0]],
     "profile_count": 3, "points_per_profile": 8, "joint": {"type": "hinge", "axis": [1, 0, 0]}},
]
CLIP = {
    "name": "bend", "duration": 1.0, "loop": "loop",
    "parts": [
        {"part": "base", "boundary": [{"time": 0, "boundary": "cantilever_free"}],
         "tip_force": {"keys": [[0, [0, 0, 0]], [1, [20, 0, 0]]]},
         "axial_point_loads": [{"at": 0.5, "force": 3.0}]},
        {"part": "arm",
         "joint_angles": {"keys": [[0, [0, 0, 0]], [0.5, [30, 0, 10], "cubic"], [1, [0, 0, 0]]]},
         "point_loads": [{"at": 0.7, "magnitude": 5, "direction": [1, 0, 0]}],
         "line_loads": [{"from": 0.1, "to": 0.9, "force_per_length": [0, 0, 2]}]}],
    "profiles": [
        {"part": "arm", "profiles": [1], "from": 0.2, "to": 0.8, "boundary": "clamped",
         "point_loads": [{"at": 0.5, "magnitude": 1, "direction": [1, 0, 0]}]}],
}


def cylinder_obj(radial=8, rings=6):
    lines = []
    for j in range(rings + 1):
        for i in range(radial):
            a = 2 * math.pi * i / radial
            lines.append(f"v {0.1 * math.cos(a):.4f} {j / rings:.4f} {0.1 * math.sin(a):.4f}")
    for j in range(rings):
        for i in range(radial):
            a = j * radial + i + 1
            b = j * radial + (i + 1) % radial + 1
            lines.append(f"f {a} {a + radial} {b + radial} {b}")
    return "\n".join(lines) + "\n"


def scene(name, kind, loop):
    clip = dict(CLIP, loop=loop)
    document = {"format": "wirerig.scene", "version": 1, "name": name,
                "mesh": {"procedural": "cylinder", "parameters": {
                    "radius": 0.1, "height": 1.0, "radial_segments": 8, "height_segments": 6}},
                "rig": {"description": {"parts": PARTS}}, "default_kind": kind, "clips": [clip]}
    if kind == "deformable":  # wires and flesh with inertia: the .wclip records their motion
        document["playback"] = {"wires": {"modes": 3, "damping_ratio": 0.2},
                                "profile_wires": {"modes": 2, "damping_ratio": 0.3,
                                                  "frequency": 3.0}}
    return document


def fresh(target):
    folder = CORPUS / target
    folder.mkdir(parents=True, exist_ok=True)
    for f in folder.iterdir():
        if not f.name.startswith("finding-"):
            f.unlink()
    return folder


def dump(path, document):
    path.write_text(json.dumps(document, indent=1) + "\n")


def clip_seeds():
    """Every clip of the sample scenes (motion clips left out), its parts renamed to the fuzz
    rig's "base" and "arm"."""
    for scene_file in sorted(REPO.glob("samples/*/*.scene.json")):
        document = json.loads(scene_file.read_text())
        for i, clip in enumerate(document.get("clips", [])):
            if "motion" in clip:
                continue
            names = {}
            for group in ("parts", "profiles"):
                for entry in clip.get(group, []):
                    names.setdefault(entry["part"], ["base", "arm"][len(names) % 2])
            clip["parts"] = [p for p in clip.get("parts", [])][:2]
            for group in ("parts", "profiles"):
                for entry in clip.get(group, []):
                    entry["part"] = names[entry["part"]]
            if len(clip["parts"]) == 2 and clip["parts"][0]["part"] == clip["parts"][1]["part"]:
                clip["parts"].pop()
            yield f"{scene_file.stem.replace('.scene', '')}_{i}.json", clip


def dictionary_tokens(documents):
    tokens = {'{', '}', '[', ']', ':', ',', '"', 'true', 'false', 'null', '-0', '1e308', '0.5',
              'NaN', 'Infinity', '\\u0000', '1e-320'}

    def walk(value):
        if isinstance(value, dict):
            for k, v in value.items():
                tokens.add(f'"{k}"')
                walk(v)
        elif isinstance(value, list):
            for v in value:
                walk(v)
        elif isinstance(value, str) and len(value) < 40 and "/" not in value:
            tokens.add(f'"{value}"')

    for d in documents:
        walk(d)
    return sorted(tokens)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--wirerig", required=True, help="the wirerig command (a release build)")
    parser.add_argument("--assimp-models", default="/usr/share/assimp/models")
    args = parser.parse_args()
    models = pathlib.Path(args.assimp_models)
    wirerig = pathlib.Path(args.wirerig).resolve()
    documents = []

    with tempfile.TemporaryDirectory() as tmp:
        tmp = pathlib.Path(tmp)
        (tmp / "cyl.obj").write_text(cylinder_obj())
        description = {"mesh": "cyl.obj", "parts": PARTS}
        dump(tmp / "cyl.description.json", description)
        subprocess.run([wirerig, "rig", "cyl.obj", "--description", "cyl.description.json",
                        "-o", "cyl.rig.json"], check=True, stdout=subprocess.DEVNULL, cwd=tmp)
        for name, kind, loop, fps in (("jointed", "deformable", "loop", "4"),
                                      ("jointed_rigid", "rigid", "ping_pong", "3")):
            dump(tmp / f"{name}.scene.json", scene(name, kind, loop))
            subprocess.run([wirerig, "build", tmp / f"{name}.scene.json", "-o",
                            tmp / f"{name}.wrig", "--clips", "--fps", fps],
                           check=True, stdout=subprocess.DEVNULL)

        out = fresh("wire_problem")
        shutil.copy(REPO / "samples/worked_wire/steel_cantilever.json", out)
        for name, document in WIRE_SEEDS.items():
            dump(out / name, document)
            documents.append(document)

        out = fresh("rig_description")
        for f in REPO.glob("samples/rigs/*.description.json"):
            shutil.copy(f, out)
            documents.append(json.loads(f.read_text()))
        shutil.copy(tmp / "cyl.description.json", out)

        out = fresh("rig_file")
        shutil.copy(tmp / "cyl.rig.json", out)
        documents.append(json.loads((tmp / "cyl.rig.json").read_text()))

        out = fresh("scene")
        for f in REPO.glob("samples/*/*.scene.json"):
            if f.stat().st_size <= 32 * 1024:
                shutil.copy(f, out)
                documents.append(json.loads(f.read_text()))
        for name in ("jointed", "jointed_rigid"):
            shutil.copy(tmp / f"{name}.scene.json", out)

        out = fresh("clip")
        dump(out / "jointed.json", CLIP)
        for name, clip in clip_seeds():
            dump(out / name, clip)

        out = fresh("bvh")
        (out / "three_joints.bvh").write_text(BVH_SEED)
        cmu = (models / "BVH/01_01.bvh").read_text().splitlines()
        motion = cmu.index("MOTION")
        (out / "cmu_01_01_head.bvh").write_text(
            "\n".join(cmu[:motion] + ["MOTION", "Frames: 4", cmu[motion + 2]] +
                      cmu[motion + 3:motion + 7]) + "\n")

        out = fresh("rig_asset")
        for name in ("jointed", "jointed_rigid"):
            shutil.copy(tmp / f"{name}.wrig", out)

        out = fresh("clip_asset")
        for name in ("jointed", "jointed_rigid"):
            shutil.copy(tmp / f"{name}.bend.wclip", out)

    out = fresh("mesh_import")
    for source, extension in MESH_SEEDS:
        data = (models / source).read_bytes()
        name = source.replace("/", "_").replace(".", "_") + "." + extension
        (out / name).write_bytes(bytes([EXTENSIONS.index(extension)]) + data)
    obj = bytes([EXTENSIONS.index("obj")]) + cylinder_obj().encode()
    (out / "cylinder.obj").write_bytes(obj)
    # What crashed or hung Assimp 5.2.5 (tests/rig/isolated_import_test.cpp).
    (out / "ply_without_end_header.ply").write_bytes(
        bytes([EXTENSIONS.index("ply")]) + b"ply\nformat ascii 1.0\nelement vertex 3\n")

    (FUZZ / "json.dict").write_text(
        "# JSON tokens and wirerig's field names and values (fuzz/make_corpus.py)\n" +
        "".join(json.dumps(t) + "\n" for t in dictionary_tokens(documents)))
    total = sum(f.stat().st_size for f in CORPUS.rglob("*") if f.is_file())
    print(f"corpus: {total} bytes")


if __name__ == "__main__":
    main()
