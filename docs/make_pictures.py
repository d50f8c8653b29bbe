"""Regenerate the README's pictures of fixtures: ``python docs/make_pictures.py``.

Each picture is ``MedialAxis3D.write_png`` of a bundled fixture (solid translucent, the
complex coloured by radius, the profile's 2D medial axis); ``viewer.png`` is the HTML viewer
of the gear wheel as headless Chromium draws it (skipped without ``chromium``).
"""

from __future__ import annotations

import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from medialcad import medial_axis, read_step  # noqa: E402

SOLIDS = ROOT / "fixtures" / "step" / "solids"
PICTURES = {
    "gear_wheel_mat.png": "gear_wheel",
    "housing_bracket_mat.png": "housing_bracket",
    "bearing_housing_mat.png": "bearing_housing",
    "spider_joint_mat.png": "spider_joint",
    "thin_plate_mat.png": "thin_plate",
}


def main() -> None:
    out = ROOT / "docs"
    for name, fixture in PICTURES.items():
        mat = medial_axis(read_step(SOLIDS / f"{fixture}.step")[0])
        mat.write_png(out / name, dpi=150 if fixture == "gear_wheel" else 70)
        print("wrote", out / name)
        if fixture == "gear_wheel":
            _viewer_shot(mat, out / "viewer.png")


def _viewer_shot(mat: object, png: Path) -> None:
    browser = shutil.which("chromium") or shutil.which("chromium-browser")
    if browser is None:
        print("chromium not found: viewer.png not made")
        return
    with tempfile.TemporaryDirectory() as tmp:
        page = Path(tmp) / "gear.html"
        mat.write_html(page)  # type: ignore[attr-defined]
        subprocess.run(
            [
                browser,
                "--headless",
                "--no-sandbox",
                "--use-angle=swiftshader",
                "--enable-unsafe-swiftshader",
                f"--user-data-dir={tmp}/profile",
                "--window-size=1000,640",
                "--virtual-time-budget=5000",
                f"--screenshot={png}",
                page.as_uri(),
            ],
            check=True,
            capture_output=True,
        )
    print("wrote", png)


if __name__ == "__main__":
    main()
