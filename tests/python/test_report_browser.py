"""The HTML report in a real browser: headless Chromium loads `surfcomp report`'s page offline
without an error, and a screenshot of its viewer shows the coloured surfaces, not a blank canvas.
"""
import pathlib
import re
import shutil
import tempfile

import pytest
from PIL import Image

from conftest import run

CHROMIUM = shutil.which("chromium")
pytestmark = pytest.mark.skipif(CHROMIUM is None, reason="chromium is not installed")

# As the machine's browser probe starts it: no sandbox as root, software WebGL, no background
# connections (the machine has no network; the page must not need one either).
FLAGS = ["--headless", "--no-sandbox", "--disable-gpu", "--enable-unsafe-swiftshader",
         "--disable-quic", "--no-first-run", "--disable-background-networking",
         "--disable-component-update", "--disable-sync", "--window-size=1400,1000",
         "--virtual-time-budget=10000"]


def chromium(url, *extra):
    with tempfile.TemporaryDirectory() as profile:
        result = run([CHROMIUM, *FLAGS, f"--user-data-dir={profile}", *extra, url], timeout=180)
    assert result.returncode == 0, result.stderr[-2000:]
    return result


def page_state(url):
    """The attributes of the page's <body> after load (the page's own error hooks count console
    errors, uncaught exceptions and refused requests into data-errors)."""
    dom = chromium(url, "--dump-dom").stdout
    body = re.search(r"<body([^>]*)>", dom)
    assert body, dom[:500]
    return dict(re.findall(r'data-([\w-]+)="([^"]*)"', body.group(1))), dom


def viewer_pixels(url, rect, path):
    chromium(url, f"--screenshot={path}")
    x, y, w, h = (int(v) for v in rect.split(","))
    return Image.open(path).convert("RGB").crop((x, y, x + w, y + h))


def colour_census(image):
    """Distinct colours (5 bits per channel), and the shares of non-white, reddish and bluish
    pixels."""
    pixels = list(image.getdata())
    distinct = {(r >> 3, g >> 3, b >> 3) for r, g, b in pixels}
    painted = sum(1 for r, g, b in pixels if min(r, g, b) < 235) / len(pixels)
    red = sum(1 for r, g, b in pixels if r > g + 30 and r > b + 30) / len(pixels)
    blue = sum(1 for r, g, b in pixels if b > r + 30 and b > g + 10) / len(pixels)
    return len(distinct), painted, red, blue


@pytest.fixture(scope="module")
def ligand_report(program, cache, tmp_path_factory):
    out = tmp_path_factory.mktemp("report") / "1C9.html"
    data = cache / "rdkit-data"
    result = run([program, "report", data / "4i23_1C9.pdb", data / "4i24_1C9.pdb", "-o", out])
    assert result.returncode == 0, result.stderr
    assert "top overlay score" in result.stdout
    return out


def test_the_page_is_one_offline_file(ligand_report):
    text = ligand_report.read_text()
    assert "Content-Security-Policy" in text and "default-src 'none'" in text
    assert "/*SURFCOMP_" not in text  # both placeholders filled
    assert not re.search(r"""(src|href)=["']https?:""", text)


def test_chromium_loads_it_without_an_error(ligand_report):
    state, _ = page_state(ligand_report.as_uri())
    assert state["status"] == "ready"
    assert state["errors"] == "0"
    assert state["selected"] == "0"
    assert state["coloring"] == "esp"


def test_the_viewer_shows_coloured_surfaces(ligand_report, tmp_path):
    state, _ = page_state(ligand_report.as_uri())
    image = viewer_pixels(ligand_report.as_uri(), state["viewer-rect"], tmp_path / "esp.png")
    distinct, painted, red, blue = colour_census(image)
    # Measured on the 1C9 pair: 4,835 distinct colours, a fifth of the viewer painted, 3 % of it
    # red and 6 % blue. A blank canvas has 1 colour; ESP colours a ligand both red and blue.
    assert distinct > 300
    assert painted > 0.10
    assert red > 0.002 and blue > 0.002


def test_another_alignment_and_colouring_change_the_picture(ligand_report, tmp_path):
    state, _ = page_state(ligand_report.as_uri())
    first = viewer_pixels(ligand_report.as_uri(), state["viewer-rect"], tmp_path / "a1.png")
    url = ligand_report.as_uri() + "#alignment=4&coloring=shape_index"
    chosen, _ = page_state(url)
    assert chosen["selected"] == "3" and chosen["coloring"] == "shape_index"
    assert chosen["errors"] == "0"
    other = viewer_pixels(url, state["viewer-rect"], tmp_path / "a4.png")
    changed = sum(1 for a, b in zip(first.getdata(), other.getdata()) if a != b)
    assert changed / (first.width * first.height) > 0.05


def test_a_large_surface_is_decimated_and_the_page_says_so(program, cache, tmp_path):
    out = tmp_path / "small.html"
    data = cache / "rdkit-data"
    result = run([program, "report", data / "4i23_1C9.pdb", data / "4i24_1C9.pdb", "-o", out,
                  "--max-display-vertices", "400", "--refine-top", "2"])
    assert result.returncode == 0, result.stderr
    state, dom = page_state(out.as_uri())
    assert state["status"] == "ready" and state["errors"] == "0"
    assert re.search(r"reference surface decimated for display: \d+ -&gt; 400 vertices", dom)
    assert re.search(r"probe surface decimated for display: \d+ -&gt; 400 vertices", dom)


def test_a_binding_site_report_shows_the_pocket(program, shared, tmp_path):
    out = tmp_path / "site.html"
    thermolysin = shared / "thermolysin"
    result = run([program, "report", thermolysin / "4TMN.pdb", thermolysin / "1THL.pdb",
                  "--ref-site-ligand", "0PK", "--probe-site-ligand", "0DB", "--patch-radius", "8",
                  "-o", out])
    assert result.returncode == 0, result.stderr
    state, dom = page_state(out.as_uri())
    assert state["status"] == "ready" and state["errors"] == "0"
    assert 'id="lining-only"' in dom
    image = viewer_pixels(out.as_uri(), state["viewer-rect"], tmp_path / "site.png")
    distinct, painted, _, _ = colour_census(image)
    assert distinct > 300 and painted > 0.10


def test_a_dock_report_shows_each_pose_of_its_conformer_in_the_pocket(program, shared, tmp_path):
    out = tmp_path / "dock.html"
    thermolysin = shared / "thermolysin"
    result = run([program, "dock", thermolysin / "ligands-original" / "ligand1TMN.sdf",
                  thermolysin / "1TMN.pdb", "--site-ligand", "0ZN", "--conformers", "2",
                  "--search-chains", "6", "--search-steps", "10", "--report", out])
    assert result.returncode == 0, result.stderr
    state, dom = page_state(out.as_uri())
    assert state["status"] == "ready" and state["errors"] == "0"
    assert "<th>contact</th>" in dom and "<th>conformer</th>" in dom
    assert "ligand placed in the receptor" in dom
    image = viewer_pixels(out.as_uri(), state["viewer-rect"], tmp_path / "dock.png")
    distinct, painted, _, _ = colour_census(image)
    assert distinct > 300 and painted > 0.10
    # Another pose (of either conformer) is drawn without an error.
    chosen, dom = page_state(out.as_uri() + "#alignment=2")
    assert chosen["selected"] == "1" and chosen["errors"] == "0"
    assert re.search(r"Pose 2</b>", dom)


def test_bad_input_leaves_no_report(program, cache, tmp_path):
    out = tmp_path / "bad.html"
    bad = tmp_path / "empty.sdf"
    bad.write_text("")
    result = run([program, "report", bad, cache / "rdkit-data" / "4i24_1C9.pdb", "-o", out])
    assert result.returncode == 1
    assert len(result.stderr.strip().splitlines()) == 1 and "empty.sdf" in result.stderr
    assert not out.exists()
    result = run([program, "report", cache / "rdkit-data" / "4i23_1C9.pdb",
                  cache / "rdkit-data" / "4i24_1C9.pdb", "-o", tmp_path / "r.txt"])
    assert result.returncode == 2 and ".html" in result.stderr
