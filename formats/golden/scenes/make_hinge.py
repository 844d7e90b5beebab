#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
# Writes hinge.gltf: the smallest skinned character the `pose` golden blob is baked from. A
# floor quad (joint 0) and a flap quad (joint 1) share the hinge edge along z at x = 0; joint 1
# turns the flap about z, so the floor's visibility of the sky depends on the one joint angle.
# Clip "swing": the flap from 45 degrees over the floor to upright to 45 degrees away.
import base64
import json
import math
import struct
import sys

positions = [(0, 0, 0), (0, 0, 1), (1, 0, 0), (1, 0, 1),  # floor, normal +y
             (0, 0, 0), (0, 0, 1), (0, 1, 0), (0, 1, 1)]  # flap, normal +x (upright)
normals = [(0, 1, 0)] * 4 + [(1, 0, 0)] * 4
joints = [(0, 0, 0, 0)] * 4 + [(1, 0, 0, 0)] * 4
weights = [(1, 0, 0, 0)] * 8
indices = [0, 1, 2, 2, 1, 3, 4, 6, 5, 5, 6, 7]
times = [0.0, 0.5, 1.0]
angles = [-45.0, 0.0, 45.0]  # about z: negative leans the flap over the floor (+x)
rotations = [(0, 0, math.sin(math.radians(a) / 2), math.cos(math.radians(a) / 2)) for a in angles]
inverse_bind = [[1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]] * 2

parts = [
    ("f", [c for p in positions for c in p], 5126, "VEC3", 8),
    ("f", [c for n in normals for c in n], 5126, "VEC3", 8),
    ("B", [c for j in joints for c in j], 5121, "VEC4", 8),
    ("f", [c for w in weights for c in w], 5126, "VEC4", 8),
    ("H", indices, 5123, "SCALAR", 12),
    ("f", [c for m in inverse_bind for c in m], 5126, "MAT4", 2),
    ("f", times, 5126, "SCALAR", 3),
    ("f", [c for r in rotations for c in r], 5126, "VEC4", 3),
]
blob, views, accessors = b"", [], []
for fmt, values, component, kind, count in parts:
    data = struct.pack("<%d%s" % (len(values), fmt), *values)
    views.append({"buffer": 0, "byteOffset": len(blob), "byteLength": len(data)})
    accessor = {"bufferView": len(views) - 1, "componentType": component, "count": count,
                "type": kind}
    if len(accessors) == 0:
        accessor["min"], accessor["max"] = [0, 0, 0], [1, 1, 1]
    if len(accessors) == 6:
        accessor["min"], accessor["max"] = [0.0], [1.0]
    accessors.append(accessor)
    blob += data + b"\0" * (-len(data) % 4)

gltf = {
    "asset": {"version": "2.0", "generator": "prtkit formats/golden/scenes/make_hinge.py"},
    "scene": 0,
    "scenes": [{"nodes": [0, 1]}],
    "nodes": [
        {"name": "hinge", "mesh": 0, "skin": 0},
        {"name": "floor_joint", "children": [2]},
        {"name": "flap_joint"},
    ],
    "meshes": [{"name": "hinge", "primitives": [{
        "attributes": {"POSITION": 0, "NORMAL": 1, "JOINTS_0": 2, "WEIGHTS_0": 3},
        "indices": 4}]}],
    "skins": [{"joints": [1, 2], "inverseBindMatrices": 5, "skeleton": 1}],
    "animations": [{"name": "swing",
                    "samplers": [{"input": 6, "output": 7, "interpolation": "LINEAR"}],
                    "channels": [{"sampler": 0, "target": {"node": 2, "path": "rotation"}}]}],
    "buffers": [{"byteLength": len(blob),
                 "uri": "data:application/octet-stream;base64," +
                        base64.b64encode(blob).decode()}],
    "bufferViews": views,
    "accessors": accessors,
}
with open(sys.argv[1] if len(sys.argv) > 1 else "hinge.gltf", "w") as out:
    json.dump(gltf, out, indent=1)
    out.write("\n")
