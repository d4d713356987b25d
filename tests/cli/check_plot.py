#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""check_plot.py MESHMORPH EXAMPLES DATA WORK: `meshmorph plot` on every example mesh
(examples/meshes, which the examples' cases and scripts read) writes a 480 × 480 PNG that PIL
opens, with many colours and most of it drawn on; an SVG parses as XML; --reference gives the
quality and displacement fields; a morph with --plot writes input and output side by side
(960 × 480), an optimize out of Newton steps with a valid, improved mesh draws it too, and a
morph that misses its goal writes no picture. Bad input exits 2 naming the
file or option, before anything is written."""
import json
import pathlib
import subprocess
import sys
import xml.etree.ElementTree as ET

from PIL import Image

mm, examples, data, work = str(pathlib.Path(sys.argv[1]).resolve()), pathlib.Path(sys.argv[2]), pathlib.Path(sys.argv[3]), pathlib.Path(sys.argv[4])
work.mkdir(parents=True, exist_ok=True)
annulus = examples / "meshes" / "annulus.msh"


def run(*args, expect=0, cwd=None):
    p = subprocess.run([mm, "-q", *map(str, args)], capture_output=True, text=True, cwd=cwd)
    if p.returncode != expect:
        sys.exit(f"FAIL: meshmorph {' '.join(map(str, args))}: exit {p.returncode}, expected {expect}\n{p.stderr}")
    return p


def check_png(path, width, height):
    """The PNG's size, and in each panel's (480 wide) mesh box a mesh: several colours, not
    grey (text, axes) over a tenth of the box at least."""
    with Image.open(path) as image:
        assert image.format == "PNG", path
        assert image.size == (width, height), f"{path}: {image.size}, expected {(width, height)}"
        rgb = image.convert("RGB")
    for left in range(0, width, 480):
        box = (left + 12, 28, left + 388, 336)
        colours = rgb.crop(box).getcolors(maxcolors=1 << 20)
        drawn = sum(n for n, (r, g, b) in colours if not r == g == b)
        assert len(colours) >= 3, f"{path}: {len(colours)} colours in {box}"
        assert drawn > 0.1 * (box[2] - box[0]) * (box[3] - box[1]), f"{path}: {drawn} pixels drawn in {box}"


def fails(args, expect_in, written=None):
    """Exit 2, with every word of `expect_in` in the message, and `written` not created."""
    p = run(*args, expect=2)
    for word in expect_in:
        assert word in p.stderr, f"meshmorph {' '.join(map(str, args))}: {word!r} not in {p.stderr!r}"
    assert written is None or not written.exists(), f"{written} was written"


for mesh in sorted((examples / "meshes").glob("*.msh")):
    out = work / (mesh.stem + ".png")
    run("plot", mesh, "-o", out)
    check_png(out, 480, 480)
    print("ok", mesh.name)

svg = work / "annulus.svg"
run("plot", annulus, "-o", svg, "--field", "scaled_jacobian")
root = ET.parse(svg).getroot()
assert root.tag == "{http://www.w3.org/2000/svg}svg" and root.get("width", "").startswith("480"), root.attrib
assert len(list(root.iter("{http://www.w3.org/2000/svg}path"))) > 1000, "the SVG holds no cells"

# A morph with --plot; then its output against its input.
case = json.loads((examples / "01_rotate_annulus" / "case.json").read_text())
case["mesh"] = str(annulus.resolve())
case.update(output="morph.vtu", report="morph.json")
(work / "case.json").write_text(json.dumps(case))
run("morph", "case.json", "--plot", "morph.png", cwd=work)
check_png(work / "morph.png", 960, 480)
p = run("plot", work / "morph.vtu", "--reference", annulus, "-o", work / "quality.png")
assert "quality min 0.49" in p.stdout, p.stdout  # the morph's minimum quality against the input
check_png(work / "quality.png", 480, 480)
run("plot", work / "morph.vtu", "--reference", annulus, "--field", "displacement", "-o", work / "moved.png")
check_png(work / "moved.png", 480, 480)
print("ok morph --plot, --reference")

missed = dict(case, boundary=[{"group": "inner", "rotate": {"center": [0, 0], "degrees": 150}},
                              {"group": "outer", "fixed": True}], options={"method": "laplace"}, output="missed.vtu")
(work / "missed.json").write_text(json.dumps(missed))
run("morph", "missed.json", "--plot", "missed.png", expect=1, cwd=work)
assert not (work / "missed.png").exists() and not (work / "missed.vtu").exists()
print("ok no picture where the goal is missed")

run("optimize", annulus, "--max-newton", "1", "-o", work / "improved.vtu", "--plot", work / "improved.png", expect=1)
assert (work / "improved.vtu").exists()
check_png(work / "improved.png", 960, 480)
print("ok a picture of the improved mesh where the run stops short")

fails(["plot", work / "nothing.msh", "-o", work / "x.png"], ["nothing.msh"], work / "x.png")
fails(["plot", data / "bad" / "msh41_truncated.msh", "-o", work / "x.png"], ["msh41_truncated.msh"], work / "x.png")
fails(["plot", annulus, "--field", "colour", "-o", work / "x.png"], ["--field", "colour"], work / "x.png")
fails(["plot", annulus, "-o", work / "x.jpg"], ["x.jpg", ".png"], work / "x.jpg")
fails(["plot", annulus, "--field", "quality", "-o", work / "x.png"], ["--reference"], work / "x.png")
fails(["plot", annulus, "--reference", examples / "meshes" / "obstacle_2d.msh", "-o", work / "x.png"],
      ["obstacle_2d.msh", "annulus.msh"], work / "x.png")
fails(["morph", work / "case.json", "-o", work / "y.vtu", "--plot", work / "y.txt"], ["--plot", "y.txt"], work / "y.vtu")
print("ok bad input exits 2")
