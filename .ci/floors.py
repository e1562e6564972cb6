"""Print pip requirement pins for the lowest versions pyproject.toml allows: each runtime
dependency declared as ``name>=X.Y`` becomes ``name==X.Y.*`` (the newest patch release of the
floor), one per line. Exits 1 when a dependency has no ``>=`` floor or when this Python is
not the lowest one ``requires-python`` allows (the run would then not be on the floors)."""
import re
import sys
import tomllib
from pathlib import Path

project = tomllib.loads((Path(__file__).resolve().parents[1] / "pyproject.toml")
                        .read_text(encoding="utf-8"))["project"]
python_floor = re.fullmatch(r">=\s*(\d+)\.(\d+)", project["requires-python"])
if python_floor is None or sys.version_info[:2] != tuple(map(int, python_floor.groups())):
    sys.exit(f"floors: this is Python {sys.version_info[0]}.{sys.version_info[1]}, "
             f"requires-python is {project['requires-python']!r}")
for requirement in project["dependencies"]:
    if ";" in requirement:          # an environment marker: not for this Python
        continue
    match = re.fullmatch(r"([A-Za-z0-9_.\-\[\]]+)\s*>=\s*([0-9.]+)", requirement.strip())
    if match is None:
        sys.exit(f"floors: {requirement!r} has no '>=' floor")
    print(f"{match[1]}=={match[2]}.*")
