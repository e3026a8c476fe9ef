#!/usr/bin/env python3
"""`$(find xacro)/xacro` as a command: robomodel's xacro (same output as ROS xacro 2.1.1)."""

import sys

from robomodel.cli.main import main

sys.exit(main(["xacro", *sys.argv[1:]]))
