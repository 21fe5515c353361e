"""Blender Line Art as a peer of vismap (bench/run_all, section f): times Line Art's
computation of the visible feature lines of an OFF mesh in vismap's view.

    blender -b --factory-startup -t N --python bench/lineart_blender.py -- \\
        SCENE.off (--dir X,Y,Z | --eye X,Y,Z [--target X,Y,Z] [--fov DEG]) OUT.json [--reps 3]
        [--crease DEG]

What it does (Blender 3.x; checked with Debian's 3.4.1):
  * reads the OFF mesh itself (Blender 3.4 has no OFF importer) into one mesh object
    (flat shaded, no auto smooth: Line Art's crease angle is then the modifier's);
  * a camera for vismap's view: --dir d is orthographic along d with vismap's screen axes
    r = d x up / |.|, u = r x d (up = +z, +y when d is vertical); --eye/--target/--fov is a
    perspective camera at the eye looking at the target (default: the bounding box's
    centre) with that vertical field of view (default 40), square frame;
  * a Grease Pencil object with a Line Art modifier on the whole scene collection, with
    crease threshold 180 degrees (every edge between two non-coplanar faces is a crease:
    vismap's --crease 0), or 180 - DEG with --crease DEG (Line Art makes an edge a crease
    where its faces' normals have n1.n2 < cos(180 degrees - threshold), i.e. turn by more
    than DEG: vismap's --crease DEG), contours, borders/loose edges and intersections on,
    no chaining across gaps (chaining_image_threshold 0), no smoothing, no stroke depth
    offset;
  * times the Line Art evaluation only: the scene is first evaluated with the modifier
    off (mesh, camera: everything but Line Art), then the modifier is switched on and the
    depsgraph update that runs it is timed (time.perf_counter, wall; time.process_time,
    CPU of the whole process); repeated --reps times (the modifier off and on again);
  * measures the strokes it produced: their total length projected on the camera plane in
    vismap's screen units (orthographic: x = r.p, y = u.p; perspective: x = r.(p-eye) /
    (f.(p-eye)) / tan(fov/2), likewise y), to compare with vismap's exact visible length.

Writes OUT.json: {"seconds": [...], "cpu_seconds": [...], "threads": N, "strokes": ...,
"points": ..., "length": ..., "frame": [xmin, xmax, ymin, ymax], ...}.
"""

import json
import math
import os
import sys
import time

import bpy
from mathutils import Matrix, Vector


def die(msg):
    print(f"lineart_blender: {msg}", file=sys.stderr)
    sys.stdout.flush()
    os._exit(1)


def parse_args():
    argv = sys.argv
    if "--" not in argv:
        die("usage: blender -b --factory-startup -t N --python lineart_blender.py -- SCENE.off VIEW OUT.json")
    args = argv[argv.index("--") + 1:]
    threads = None
    for k, a in enumerate(argv[:argv.index("--")]):
        if a in ("-t", "--threads") and k + 1 < len(argv):
            threads = int(argv[k + 1])
    opts = {"dir": None, "eye": None, "target": None, "fov": None, "reps": 3, "crease": 0.0}
    pos = []
    k = 0
    while k < len(args):
        a = args[k]
        if a in ("--dir", "--eye", "--target"):
            v = [float(x) for x in args[k + 1].split(",")]
            if len(v) != 3:
                die(f"{a} needs X,Y,Z")
            opts[a[2:]] = v
            k += 2
        elif a == "--fov":
            opts["fov"] = float(args[k + 1])
            k += 2
        elif a == "--reps":
            opts["reps"] = int(args[k + 1])
            k += 2
        elif a == "--crease":   # vismap's crease angle: Line Art's threshold is 180 - DEG
            opts["crease"] = float(args[k + 1])
            if not 0 <= opts["crease"] <= 180:
                die("--crease must be between 0 and 180 degrees")
            k += 2
        else:
            pos.append(a)
            k += 1
    if len(pos) != 2:
        die("needs SCENE.off and OUT.json")
    if opts["dir"] and (opts["eye"] or opts["target"] or opts["fov"]):
        die("--dir cannot be combined with --eye/--target/--fov")
    if not opts["dir"] and not opts["eye"]:
        die("needs --dir or --eye")
    return pos[0], pos[1], opts, threads


def read_off(path):
    """A small OFF reader: OFF header (counts on the same line or the next), # comments,
    faces as 'n i0 ... i(n-1)' (anything after the indices, e.g. a colour, is ignored)."""
    with open(path) as f:
        text = f.read()
    toks = []
    for line in text.splitlines():
        line = line.split("#", 1)[0]
        if line.strip():
            toks.append(line.split())
    if not toks or not toks[0][0].endswith("OFF"):
        die(f"{path}: not an OFF file")
    head = toks[0][1:]
    rows = toks[1:]
    if not head:
        head, rows = rows[0], rows[1:]
    nv, nf = int(head[0]), int(head[1])
    verts = [(float(r[0]), float(r[1]), float(r[2])) for r in rows[:nv]]
    faces = []
    for r in rows[nv:nv + nf]:
        n = int(r[0])
        faces.append(tuple(int(x) for x in r[1:1 + n]))
    if len(verts) != nv or len(faces) != nf:
        die(f"{path}: truncated")
    return verts, faces


def sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def unit(a):
    n = math.sqrt(dot(a, a))
    return (a[0] / n, a[1] / n, a[2] / n)


def frame(d):
    """vismap's frame (engine/camera.cpp make_frame): r = d x up, u = r x d, f = d."""
    up = (0.0, 0.0, 1.0)
    ru = cross(d, up)
    if dot(ru, ru) == 0:
        up = (0.0, 1.0, 0.0)
        ru = cross(d, up)
    r = unit(ru)
    u = unit(cross(r, d))
    return r, u, unit(d)


def main():
    scene_path, out_path, opts, threads = parse_args()
    verts, faces = read_off(scene_path)

    # A clean scene: --factory-startup still has the cube, light and camera.
    for ob in list(bpy.data.objects):
        bpy.data.objects.remove(ob, do_unlink=True)
    scene = bpy.context.scene

    me = bpy.data.meshes.new("mesh")
    me.from_pydata(verts, [], faces)
    me.update()
    mesh_ob = bpy.data.objects.new("mesh", me)
    scene.collection.objects.link(mesh_ob)

    lo = [min(v[i] for v in verts) for i in range(3)]
    hi = [max(v[i] for v in verts) for i in range(3)]
    centre = tuple((lo[i] + hi[i]) / 2 for i in range(3))
    radius = math.sqrt(sum((hi[i] - lo[i]) ** 2 for i in range(3))) / 2 or 1.0
    corners = [(x, y, z) for x in (lo[0], hi[0]) for y in (lo[1], hi[1]) for z in (lo[2], hi[2])]

    cam_data = bpy.data.cameras.new("camera")
    cam = bpy.data.objects.new("camera", cam_data)
    scene.collection.objects.link(cam)
    scene.camera = cam
    scene.render.resolution_x = scene.render.resolution_y = 1000
    scene.render.pixel_aspect_x = scene.render.pixel_aspect_y = 1
    if opts["dir"]:
        r, u, f = frame(opts["dir"])
        xs = [dot(r, sub(c, centre)) for c in corners]
        ys = [dot(u, sub(c, centre)) for c in corners]
        cam_data.type = "ORTHO"
        cam_data.ortho_scale = 2.2 * max(max(abs(x) for x in xs), max(abs(y) for y in ys), 1e-9)
        eye = tuple(centre[i] - f[i] * 3 * radius for i in range(3))
        cam_data.clip_start = radius * 1e-3
        cam_data.clip_end = radius * 10
        t = None
    else:
        eye = tuple(opts["eye"])
        target = tuple(opts["target"]) if opts["target"] else centre
        fov = opts["fov"] if opts["fov"] else 40.0
        r, u, f = frame(sub(target, eye))
        t = math.tan(math.radians(fov) / 2)
        cam_data.type = "PERSP"
        cam_data.sensor_fit = "VERTICAL"
        cam_data.angle_y = math.radians(fov)
        dist = math.sqrt(dot(sub(target, eye), sub(target, eye)))
        cam_data.clip_start = dist * 1e-3   # vismap's near plane
        cam_data.clip_end = (dist + 2 * radius) * 10
    # Camera: local -Z along f, +Y along u, +X along r.
    cam.matrix_world = Matrix(((r[0], u[0], -f[0], eye[0]),
                               (r[1], u[1], -f[1], eye[1]),
                               (r[2], u[2], -f[2], eye[2]),
                               (0, 0, 0, 1)))

    gp = bpy.data.grease_pencils.new("lineart")
    gp_ob = bpy.data.objects.new("lineart", gp)
    scene.collection.objects.link(gp_ob)
    layer = gp.layers.new("lines")
    layer.frames.new(scene.frame_current)
    mat = bpy.data.materials.new("lines")
    bpy.data.materials.create_gpencil_data(mat)
    gp.materials.append(mat)
    mod = gp_ob.grease_pencil_modifiers.new("lineart", "GP_LINEART")
    mod.source_type = "SCENE"
    mod.target_layer = "lines"
    mod.target_material = mat
    settings = {
        # every edge between non-coplanar faces is a crease (--crease 0); 180 - DEG for --crease DEG
        "crease_threshold": math.pi - math.radians(opts["crease"]),
        "use_crease": True,
        "use_crease_on_smooth": True,
        "use_crease_on_sharp": True,
        "use_contour": True,
        "use_loose": True,
        "use_intersection": True,
        "use_material": False,
        "use_edge_mark": False,
        "use_back_face_culling": False,
        "use_image_boundary_trimming": False,
        "use_clip_plane_boundaries": True,
        "use_overlap_edge_type_support": False,
        "use_edge_overlap": False,
        "chaining_image_threshold": 0.0,
        "use_detail_preserve": True,
        "smooth_tolerance": 0.0,
        "split_angle": 0.0,
        "stroke_depth_offset": 0.0,
        "use_multiple_levels": False,
        "level_start": 0,
        "level_end": 0,
        "use_cache": False,
    }
    for k, v in settings.items():
        if hasattr(mod, k):
            setattr(mod, k, v)

    # Everything but Line Art first, then Line Art alone, timed.
    mod.show_viewport = False
    depsgraph = bpy.context.evaluated_depsgraph_get()
    depsgraph.update()
    seconds, cpu = [], []
    for rep in range(max(1, opts["reps"])):
        mod.show_viewport = False
        depsgraph.update()
        mod.show_viewport = True
        c0, t0 = time.process_time(), time.perf_counter()
        depsgraph.update()
        t1, c1 = time.perf_counter(), time.process_time()
        seconds.append(t1 - t0)
        cpu.append(c1 - c0)

    # The strokes (outside the timing), projected to vismap's screen.
    gp_eval = gp_ob.evaluated_get(depsgraph)
    if t is None:
        def project(p):
            return dot(r, p), dot(u, p)
    else:
        def project(p):
            q = sub(p, eye)
            w = dot(f, q)
            return dot(r, q) / w / t, dot(u, q) / w / t
    length, nstrokes, npoints = 0.0, 0, 0
    behind = 0
    xmin = ymin = math.inf
    xmax = ymax = -math.inf
    mw = gp_eval.matrix_world
    identity = all(abs(mw[i][j] - (1.0 if i == j else 0.0)) < 1e-12 for i in range(4) for j in range(4))
    for lay in gp_eval.data.layers:
        for fr in lay.frames:
            for s in fr.strokes:
                n = len(s.points)
                co = [0.0] * (3 * n)
                s.points.foreach_get("co", co)
                pts = []
                for i in range(n):
                    p = (co[3 * i], co[3 * i + 1], co[3 * i + 2])
                    if not identity:
                        p = tuple(mw @ Vector(p))
                    if t is not None and dot(f, sub(p, eye)) <= 0:
                        behind += 1
                        continue
                    pts.append(project(p))
                nstrokes += 1
                npoints += n
                for (x0, y0), (x1, y1) in zip(pts, pts[1:]):
                    length += math.hypot(x1 - x0, y1 - y0)
                for x, y in pts:
                    xmin, xmax, ymin, ymax = min(xmin, x), max(xmax, x), min(ymin, y), max(ymax, y)
    out = {
        "scene": os.path.basename(scene_path),
        "faces": len(faces),
        "view": {k: opts[k] for k in ("dir", "eye", "target", "fov") if opts[k] is not None},
        "crease": opts["crease"],
        "threads": threads,
        "blender": bpy.app.version_string,
        "seconds": seconds,
        "cpu_seconds": cpu,
        "strokes": nstrokes,
        "points": npoints,
        "points_behind_eye": behind,
        "length": length,
        "frame": [xmin, xmax, ymin, ymax] if nstrokes else None,
        "settings": {k: v for k, v in settings.items() if hasattr(mod, k)},
    }
    with open(out_path, "w") as fo:
        json.dump(out, fo, indent=1)
    print(f"lineart_blender: {out['scene']}: Line Art {min(seconds):.3f}..{max(seconds):.3f} s wall, "
          f"{nstrokes} strokes, length {length:.6g}", file=sys.stderr)
    sys.stdout.flush()
    sys.stderr.flush()
    os._exit(0)   # (skip Blender's slow teardown)


try:
    main()
except SystemExit:
    raise
except BaseException as e:   # Blender would otherwise go on to its (empty) event loop
    import traceback
    traceback.print_exc()
    sys.stderr.flush()
    os._exit(1)
