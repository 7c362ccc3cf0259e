"""The layout's limits (docs/architecture.md): no source file in solver/, engine/, app/ or gpu/
over 600 lines, and the one-way dependencies (solver and gpu include nothing of engine or app,
engine nothing of app)."""
import pathlib
import re

SOURCE = pathlib.Path(__file__).resolve().parents[2]
SUFFIXES = {".h", ".cpp", ".cu", ".cuh"}


def sources(folder):
    return [p for p in sorted((SOURCE / folder).rglob("*")) if p.suffix in SUFFIXES]


def test_no_source_file_is_over_600_lines():
    long = [f"{p.relative_to(SOURCE)}: {n} lines"
            for folder in ("solver", "engine", "app", "gpu") for p in sources(folder)
            if (n := len(p.read_text().splitlines())) > 600]
    assert not long, "\n".join(long)


def test_dependencies_point_one_way():
    forbidden = {"solver": ("engine/", "app/", "gpu/"), "gpu": ("engine/", "app/"),
                 "engine": ("app/",)}
    wrong = []
    for folder, layers in forbidden.items():
        for p in sources(folder):
            for included in re.findall(r'#include "([^"]+)"', p.read_text()):
                if included.startswith(layers):
                    wrong.append(f"{p.relative_to(SOURCE)} includes {included}")
    assert not wrong, "\n".join(wrong)
