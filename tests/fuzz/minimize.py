#!/usr/bin/env python3
# Usage: tests/fuzz/minimize.py SCENE.off "VISMAP OPTIONS" "VERIFY OPTIONS" OUT.off
# (VISMAP=path/to/vismap to pick the binary): drops faces one by one while the
# map still fails vismap verify (or the engine crashes), then unused vertices.
# MODE=crash keeps only an engine failure (an internal error, status 3, or a
# signal); MODE=verify only a map that vismap verify rejects.
# Shrinks an OFF scene while `vismap SCENE ARGS --json m && vismap verify SCENE m VARGS` keeps failing.
import subprocess, sys, os, tempfile
V = os.environ.get('VISMAP', 'build/vismap')
src, args, vargs = sys.argv[1], sys.argv[2].split(), sys.argv[3].split() if len(sys.argv) > 3 else []
lines = [l for l in open(src).read().split('\n') if l.strip() and not l.startswith('#')]
nv, nf = map(int, lines[1].split()[:2])
verts = [l for l in lines[2:2+nv]]
faces = [l for l in lines[2+nv:2+nv+nf]]
d = tempfile.mkdtemp()
def write(vs, fs, path):
    open(path, 'w').write("OFF\n%d %d 0\n" % (len(vs), len(fs)) + "\n".join(vs) + "\n" + "\n".join(fs) + "\n")
def fails(vs, fs):
    p = os.path.join(d, 's.off'); m = os.path.join(d, 'm.json')
    write(vs, fs, p)
    mode = os.environ.get('MODE', 'any')
    r = subprocess.run([V, p] + args + ['--json', m], capture_output=True)
    if r.returncode != 0: return mode != 'verify' and r.returncode not in (0, 1, 2)  # crash counts
    if mode == 'crash': return False
    r = subprocess.run([V, 'verify', p, m] + vargs, capture_output=True)
    return r.returncode == 1
assert fails(verts, faces), "does not fail"
changed = True
while changed:
    changed = False
    for i in range(len(faces)):
        if i >= len(faces): break
        f2 = faces[:i] + faces[i+1:]
        if f2 and fails(verts, f2):
            faces = f2; changed = True
# drop unused vertices
used = sorted({int(x) for f in faces for x in f.split()[1:]})
remap = {o: n for n, o in enumerate(used)}
verts2 = [verts[o] for o in used]
faces2 = [" ".join([f.split()[0]] + [str(remap[int(x)]) for x in f.split()[1:]]) for f in faces]
assert fails(verts2, faces2)
write(verts2, faces2, sys.argv[4] if len(sys.argv) > 4 else '/dev/stdout')
