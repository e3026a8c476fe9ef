"""Put ``robomodel-clientlibs.pth`` in this interpreter's site-packages, as the wheel does.

An editable install (``pip install -e .``) leaves the file out: setuptools builds the editable
wheel without the ``build_py`` step of setup.py that adds it. ``make`` runs this after it.
"""

from __future__ import annotations

import shutil
import sysconfig
from pathlib import Path

SOURCE = Path(__file__).resolve().parent.parent / "src" / "robomodel-clientlibs.pth"


def main() -> None:
    target = Path(sysconfig.get_paths()["purelib"]) / SOURCE.name
    shutil.copyfile(SOURCE, target)
    print(f"installed {target}")


if __name__ == "__main__":
    main()
