"""Prints what a launch or `robomodel run` gave it, as JSON on one line, then ends (or waits)."""

import json
import os
import pathlib
import sys
import time


def main():
    params = {}
    words = sys.argv[1:]
    for i, word in enumerate(words[:-1]):
        if word == "--params-file":
            params[words[i + 1]] = pathlib.Path(words[i + 1]).read_text()
    print(
        json.dumps(
            {
                "pid": os.getpid(),
                "argv0": sys.argv[0],
                "args": words,
                "flavour": os.environ.get("ROBOMODEL_MESSAGE_FLAVOUR"),
                "master": os.environ.get("ROS_MASTER_URI"),
                "namespace": os.environ.get("ROS_NAMESPACE"),
                "extra": os.environ.get("EXTRA"),
                "params_files": params,
            }
        ),
        flush=True,
    )
    stay_until = os.environ.get("STAY_UNTIL")
    if stay_until:
        while not os.path.exists(stay_until):
            time.sleep(0.05)
    return 0
