"""Everything is in pyproject.toml but one file: ``robomodel-clientlibs.pth``, which goes to the
top of site-packages (next to the ``robomodel`` package, not inside it) so that Python runs it at
start and ``import rclpy`` / ``from std_msgs.msg import String`` find robomodel's client
libraries (src/robomodel/clientlibs/finder.py). An editable install leaves it out; the
Makefile copies it there (tools/install_clientlibs_pth.py)."""

import os

from setuptools import setup
from setuptools.command.build_py import build_py

PTH = "robomodel-clientlibs.pth"


class BuildPyWithPth(build_py):
    def run(self) -> None:
        super().run()
        self.copy_file(os.path.join("src", PTH), os.path.join(self.build_lib, PTH))

    def get_outputs(self, include_bytecode: bool = True) -> list[str]:
        return [*super().get_outputs(include_bytecode), os.path.join(self.build_lib, PTH)]


setup(cmdclass={"build_py": BuildPyWithPth})
