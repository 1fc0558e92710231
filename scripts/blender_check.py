"""Imports mintorque's exports with Blender's stock importers and checks what Blender made of them.

Run by scripts/blender-check.sh: `blender -b --factory-startup --python scripts/blender_check.py -- FILE...`.
For a .bvh: the armature's bone count is the file's ROOT/JOINT count, the scene's frame range is
1..Frames and its frame rate (fps / fps_base) is 1 / Frame Time. For a .glb: the armature's bone count is
the skin's joint count, and the last keyframe of the animation sits at the file's last time × the scene's
frame rate (Blender 3.4 keys glTF time t at frame t·fps). Prints one line per check
and exits 1 on any mismatch.
"""
import json
import os
import struct
import sys

import bpy

failures = []


def shim_bvh_importer():
    """Blender 3.4's BVH importer opens files in mode 'rU', which Python 3.11 refuses (Debian's Blender
    runs on the system Python): its module gets an `open` that drops the 'U'."""
    import builtins
    import io_anim_bvh.import_bvh as importer

    def open_without_u(file, mode='r', *args, **kwargs):
        return builtins.open(file, mode.replace('U', ''), *args, **kwargs)

    importer.open = open_without_u


def check(what, got, want, tol=0.0):
    ok = abs(got - want) <= tol if isinstance(want, float) else got == want
    print(f"{'ok  ' if ok else 'FAIL'} {what}: Blender {got!r}, file {want!r}")
    if not ok:
        failures.append(what)


def shim_gltf_importer():
    """Blender 3.4's glTF importer uses `numpy.bool`, which NumPy 1.24 removed (Debian 12 has 1.24): the
    alias is put back (it was Python's `bool`)."""
    import numpy
    if 'bool' not in numpy.__dict__:
        numpy.bool = bool


def clear_scene():
    bpy.ops.wm.read_factory_settings(use_empty=True)
    # The factory scene ends at frame 250 and the importers only ever extend it: start from one frame.
    bpy.context.scene.frame_start = 1
    bpy.context.scene.frame_end = 1


def armatures():
    return [o for o in bpy.context.scene.objects if o.type == 'ARMATURE']


def bvh_rest_positions(tokens):
    """Each ROOT/JOINT's position at rest, its OFFSETs summed down the hierarchy (the file's unit, Y up)."""
    positions, stack, pending, k = {}, [], None, 0
    while k < len(tokens):
        word = tokens[k]
        if word in ('ROOT', 'JOINT'):
            pending = tokens[k + 1]
        elif word == 'End':
            pending = None
        elif word == '{':
            stack.append(pending)
        elif word == '}':
            stack.pop()
        elif word == 'OFFSET':
            offset = [float(v) for v in tokens[k + 1:k + 4]]
            parents = [n for n in stack[:-1] if n is not None]
            base = positions[parents[-1]] if parents else [0.0, 0.0, 0.0]
            if stack[-1] is not None:
                positions[stack[-1]] = [b + o for b, o in zip(base, offset)]
        elif word == 'MOTION':
            break
        k += 1
    return positions


def check_bone_heads(path, arm, positions, scale):
    """Every bone's rest head where the file puts its joint: BVH (x, y, z) is Blender's (x, −z, y) under the
    importer's default axes (−Z forward, Y up), times the import scale."""
    worst, where = 0.0, None
    for name, (x, y, z) in positions.items():
        head = arm.matrix_world @ arm.data.bones[name].head_local
        miss = max(abs(head[0] - x * scale), abs(head[1] + z * scale), abs(head[2] - y * scale))
        if miss > worst:
            worst, where = miss, name
    print(f"     {path}: worst bone head off its joint by {worst:.2e} m ({where})")
    check(f"{path}: bone heads at the joints (1e-4 m)", worst <= 1e-4, True)


def check_bvh(path):
    text = open(path).read().split()
    joints = sum(1 for w in text if w in ('ROOT', 'JOINT'))
    frames = int(text[text.index('Frames:') + 1])
    frame_time = float(text[text.index('Time:') + 1])
    clear_scene()
    shim_bvh_importer()
    # Centimetres to metres; the scene takes the file's frame rate and length.
    bpy.ops.import_anim.bvh(filepath=path, global_scale=0.01, update_scene_fps=True, update_scene_duration=True)
    scene = bpy.context.scene
    arms = armatures()
    check(f"{path}: one armature", len(arms), 1)
    if arms:
        check(f"{path}: bones", len(arms[0].data.bones), joints)
        check_bone_heads(path, arms[0], bvh_rest_positions(text), 0.01)
        action = arms[0].animation_data.action if arms[0].animation_data else None
        keys = [k.co[0] for c in action.fcurves for k in c.keyframe_points] if action else []
        # Frame k of the file (1-based) is keyed at scene frame k.
        check(f"{path}: first keyed frame", min(keys, default=None), 1.0, 1e-6)
        check(f"{path}: last keyed frame", max(keys, default=None), float(frames), 1e-6)
    # The importer only extends the scene, to frame_start + Frames (one past the last key).
    check(f"{path}: scene covers the frames", scene.frame_start <= 1 and scene.frame_end >= frames, True)
    check(f"{path}: frames per second", scene.render.fps / scene.render.fps_base, 1.0 / frame_time, 1e-6 / frame_time)


def glb_json(path):
    data = open(path, 'rb').read()
    (length,) = struct.unpack_from('<I', data, 12)
    return json.loads(data[20:20 + length])


def glb_last_time(path, doc):
    """The largest animation input time, from the accessor's `max` (required by glTF for inputs)."""
    inputs = {s['input'] for a in doc['animations'] for s in a['samplers']}
    return max(doc['accessors'][i]['max'][0] for i in inputs)


def check_glb(path):
    doc = glb_json(path)
    skin_joints = len(doc['skins'][0]['joints'])
    last = glb_last_time(path, doc)
    clear_scene()
    shim_gltf_importer()
    bpy.ops.import_scene.gltf(filepath=path)
    scene = bpy.context.scene
    fps = scene.render.fps / scene.render.fps_base
    arms = armatures()
    check(f"{path}: one armature", len(arms), 1)
    if arms:
        check(f"{path}: bones", len(arms[0].data.bones), skin_joints)
        action = arms[0].animation_data.action if arms[0].animation_data else None
        check(f"{path}: armature animated", action is not None, True)
        if action is not None:
            # Blender's glTF importer keys time t at frame t·fps (3.4: no offset), the scene's fps.
            end = max(k.co[0] for c in action.fcurves for k in c.keyframe_points)
            check(f"{path}: last key frame (last time {last} s × {fps} fps)", end, last * fps, 1e-3)
    skinned = [o for o in scene.objects if o.type == 'MESH' and any(m.type == 'ARMATURE' for m in o.modifiers)]
    check(f"{path}: one skinned mesh", len(skinned), 1)


def main():
    files = sys.argv[sys.argv.index('--') + 1:] if '--' in sys.argv else []
    if not files:
        print("usage: blender -b --python scripts/blender_check.py -- FILE.bvh|FILE.glb ...")
        sys.exit(2)
    print(f"Blender {bpy.app.version_string}, Python {sys.version.split()[0]}")
    for path in files:
        if not os.path.isfile(path):
            print(f"FAIL {path}: no such file")
            failures.append(path)
        elif path.endswith('.bvh'):
            check_bvh(path)
        elif path.endswith('.glb'):
            check_glb(path)
        else:
            print(f"FAIL {path}: not a .bvh or .glb")
            failures.append(path)
    print(f"{len(failures)} check(s) failed" if failures else "all checks passed")
    sys.exit(1 if failures else 0)


main()
