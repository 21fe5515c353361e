"""The Python module against the command line: the same map, byte for byte, on
the corpus; arrays that agree with the exact values; scenes from numpy; errors as
Python exceptions; files written by extension. Run by ctest (Python.Pytest),
which sets PYTHONPATH to the built module and VISMAP_BIN, VISMAP_DATA_DIR."""
import fractions
import json
import os
import re
import shlex
import subprocess

import numpy as np
import pytest

import vismap

DATA = os.environ["VISMAP_DATA_DIR"]
BIN = os.environ["VISMAP_BIN"]


def corpus():
    with open(os.path.join(DATA, "cases.txt")) as f:
        for line in f:
            line = line.rstrip("\n")
            if line and not line.startswith("#"):
                scene, _, args = line.partition("\t")
                yield scene, args


def keywords(args):
    """The compute() keywords for a case's command-line arguments."""
    kw = {}
    words = shlex.split(args)
    i = 0
    while i < len(words):
        a = words[i]
        if a == "--smooth":
            kw["smooth"] = True
            i += 1
            continue
        v = words[i + 1]
        i += 2
        if a in ("--dir", "--eye", "--target", "--up"):
            kw[a[2:]] = tuple(float(x) for x in v.split(","))
        elif a == "--fov":
            kw["fov"] = float(v)
        elif a == "--crease":
            kw["crease"] = float(v)
        else:
            raise AssertionError("the test does not know " + a)
    return kw


def cli_json(tmp_path, scene, args):
    out = tmp_path / "cli.json"
    subprocess.run([BIN, scene] + shlex.split(args) + ["--json", str(out)], check=True)
    return out.read_text()


@pytest.mark.parametrize("scene,args", list(corpus()))
def test_json_is_the_command_lines(tmp_path, scene, args):
    path = os.path.join(DATA, scene)
    kw = keywords(args)
    assert vismap.compute(path, **kw).to_json() == cli_json(tmp_path, path, args)
    assert vismap.compute(path, hidden=True, algorithm="newell", **kw).to_json() == cli_json(
        tmp_path, path, args + " --hidden --algorithm newell")
    assert vismap.compute(path, hidden=True, regions=False, **kw).to_json() == cli_json(
        tmp_path, path, args + " --hidden --no-regions")


def test_arrays_are_the_nearest_doubles_to_the_exact_values():
    m = vismap.compute(os.path.join(DATA, "perspective_box_close.off"), eye=(2, -1.5, 1.25), target=(0, 0, 0),
                       fov=90, hidden=True)
    assert m.vertices.dtype == np.float64 and m.vertices.shape == (len(m.exact_vertices()), 2)
    # float(Fraction) rounds correctly: the nearest double.
    assert [(float(x), float(y)) for x, y in m.exact_vertices()] == [tuple(p) for p in m.vertices]
    assert m.segments.shape == (len(m.segment_kinds), 2, 2)
    for (a, b), (ea, eb) in zip(m.segments, m.exact_segments()):
        assert (a[0], a[1], b[0], b[1]) == (float(ea[0]), float(ea[1]), float(eb[0]), float(eb[1]))
    assert all(isinstance(x, fractions.Fraction) for p in m.exact_vertices() for x in p)
    assert m.hidden.shape == (len(m.hidden_kinds), 2, 2) and len(m.hidden_kinds) > 0
    for (a, b), (ea, eb) in zip(m.hidden, m.exact_hidden()):
        assert (a[0], a[1], b[0], b[1]) == (float(ea[0]), float(ea[1]), float(eb[0]), float(eb[1]))
    assert set(m.segment_kinds) <= {"border", "silhouette", "crease", "smooth", "intersection"}
    # Each segment joins two of the map's vertices, from < to.
    sv = m.segment_vertices
    assert (m.vertices[sv[:, 0]] == m.segments[:, 0]).all() and (sv[:, 0] < sv[:, 1]).all()
    assert all(list(f) == sorted(f) for f in m.segment_faces)


def test_a_scene_from_numpy_gives_the_files_map(tmp_path):
    # Two squares, one above the other and shifted: the same map from arrays, from
    # lists, and from the same scene written as an OFF file.
    v = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0],
                  [0.5, 0.5, 1], [1.5, 0.5, 1], [1.5, 1.5, 1], [0.5, 1.5, 1]], dtype=np.float64)
    f = np.array([[0, 1, 2, 3], [4, 5, 6, 7]])
    off = tmp_path / "two.off"
    off.write_text("OFF\n8 2 0\n" + "".join(f"{x!r} {y!r} {z!r}\n" for x, y, z in v) +
                   "".join("4 " + " ".join(map(str, r)) + "\n" for r in f))
    from_arrays = vismap.compute(vismap.Scene(v, f, name=str(off)), dir=(0, 0, -1), hidden=True)
    from_lists = vismap.compute(vismap.Scene(v.tolist(), f.tolist(), name=str(off)), dir=(0, 0, -1), hidden=True)
    from_file = vismap.compute(str(off), dir=(0, 0, -1), hidden=True)
    assert from_arrays.to_json() == from_file.to_json() == from_lists.to_json()
    assert len(from_arrays.regions) == 2 and len(from_arrays.segments) == 10 and len(from_arrays.hidden) == 2
    face, outer, holes = from_arrays.regions[0]
    assert outer.shape[1] == 2 and holes == []
    s = vismap.read_scene(str(off))
    assert s.vertices.shape == (8, 3) and s.faces == f.tolist()


def test_a_scene_with_holes_from_python_gives_the_files_map():
    path = os.path.join(DATA, "holes_plate.vmscene.json")
    with open(path) as f:
        doc = json.load(f)
    faces, holes = [], {}
    for i, face in enumerate(doc["faces"]):
        if isinstance(face, dict):
            faces.append(face["outer"])
            holes[i] = face.get("holes", [])
        else:
            faces.append(face)
    scene = vismap.Scene(np.array(doc["vertices"], dtype=np.float64), faces, holes=holes, name=path)
    assert scene.holes == {0: holes[0]} and len(holes[0]) == 3
    assert vismap.compute(scene, dir=(-1, -2, -4), hidden=True).to_json() == \
        vismap.compute(path, dir=(-1, -2, -4), hidden=True).to_json()
    m = vismap.compute(scene, dir=(0, 0, -1))
    assert sum(len(h) for _, _, h in m.regions) >= 2   # the plate's holes, seen from above
    with pytest.raises(vismap.InputError, match="face 0 has holes, so it must be planar"):
        bent = np.array(doc["vertices"], dtype=np.float64)
        bent[4, 2] = 0.25
        vismap.compute(vismap.Scene(bent, faces, holes=holes))
    with pytest.raises(IndexError, match="holes name face 9"):
        vismap.Scene(doc["vertices"], faces, holes={9: [[0, 1, 2]]})


def test_errors_are_python_exceptions():
    with pytest.raises(vismap.InputError, match="none.off"):
        vismap.compute("/nonexistent/none.off")
    assert issubclass(vismap.InputError, ValueError)
    box = os.path.join(DATA, "cube_axis.off")
    with pytest.raises(ValueError, match="must differ"):
        vismap.compute(box, eye=(1, 1, 1), target=(1, 1, 1))
    with pytest.raises(ValueError, match="algorithm"):
        vismap.compute(box, algorithm="warnock")
    with pytest.raises(ValueError, match="three components"):
        vismap.compute(box, dir=(0, 1))
    with pytest.raises(IndexError, match="vertex 3"):
        vismap.Scene([[0, 0, 0], [1, 0, 0], [0, 1, 0]], [[0, 1, 3]])
    m = vismap.compute(box)
    with pytest.raises(ValueError, match="pastel"):
        m.to_svg(style="pastel")
    for e in (vismap.InputError, ValueError):
        try:
            vismap.compute("scene.txt")
        except e as err:
            assert "--" not in str(err)


def test_writes_by_extension_what_it_gives(tmp_path):
    m = vismap.compute(os.path.join(DATA, "interpenetrating_boxes.off"), dir=(-1, -2, -3), hidden=True)
    m.write(str(tmp_path / "m.json"))
    assert (tmp_path / "m.json").read_text() == m.to_json()
    m.write(str(tmp_path / "m.svg"), style="technical", page="a4", line=["hidden:color=red"])
    svg = (tmp_path / "m.svg").read_text()
    assert svg == m.to_svg(style="technical", page="a4", line="hidden:color=red")
    assert 'height="210.000mm"' in svg or 'height="297.000mm"' in svg
    m.write(str(tmp_path / "m.dxf"))
    assert (tmp_path / "m.dxf").read_bytes() == m.drawing("dxf")
    # The command line's drawing of the same map, byte for byte.
    out = tmp_path / "cli.svg"
    subprocess.run([BIN, os.path.join(DATA, "interpenetrating_boxes.off"), "--dir", "-1,-2,-3", "--hidden",
                    "--style", "technical", "--page", "a4", "--line", "hidden:color=red", "-o", str(out)], check=True)
    assert out.read_text() == svg


def test_readme_example_runs(tmp_path, monkeypatch):
    """The README's matplotlib example, as written (where matplotlib is installed)."""
    pytest.importorskip("matplotlib")
    import matplotlib
    matplotlib.use("Agg")
    readme = open(os.environ["VISMAP_README"]).read()
    code = re.search(r"```python\n(.*?)```", readme, re.S).group(1)
    monkeypatch.chdir(tmp_path)
    code = code.replace('"examples/boxes.off"', repr(os.path.join(os.path.dirname(os.environ["VISMAP_README"]),
                                                                  "examples", "boxes.off")))
    exec(compile(code, "README.md", "exec"), {})
    assert os.path.getsize(tmp_path / "boxes.png") > 0
