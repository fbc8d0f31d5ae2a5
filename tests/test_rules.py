"""Architecture rules, checked on the source text: precision is set only in balls.py; floats
(numpy/scipy) live only in rigor_gyro/approx; rigorous modules never import them."""
import re
from pathlib import Path

PKG = Path(__file__).resolve().parent.parent / "rigor_gyro"
RIGOROUS = [p for p in PKG.glob("*.py")]


def test_only_balls_sets_precision():
    for path in PKG.rglob("*.py"):
        text = path.read_text()
        if path.name != "balls.py":
            assert not re.search(r"ctx\.prec\s*=|ctx\.dps\s*=|workprec\(", text), path


def test_rigorous_modules_import_no_float_libraries():
    for path in RIGOROUS:
        text = path.read_text()
        assert not re.search(r"^\s*(import|from)\s+(numpy|scipy|mpmath)\b", text, re.M), path


def test_no_float_literals_fed_to_balls_in_rigorous_modules():
    """arb(0.1)-style construction from a float literal would round silently."""
    for path in RIGOROUS:
        text = path.read_text()
        assert not re.search(r"arb\(\s*-?\d+\.\d*", text), path
