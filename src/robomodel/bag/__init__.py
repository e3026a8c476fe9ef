"""Recording and replaying runs: rosbag2 folders (MCAP, SQLite 3) and ROS 1 bags.

The formats are handled by maintained libraries (Foxglove's ``mcap``, rosbags), imported when
a bag is opened: ``pip install 'robomodel[bag]'``.
"""

from robomodel.bag._mcap_writer import McapFolderWriter
from robomodel.bag._other_writers import Ros1BagWriter, Sqlite3FolderWriter
from robomodel.bag._writer_base import BagWriter, SplitPolicy
from robomodel.bag.exceptions import BagError, BagFormatError, BagWriteError
from robomodel.bag.model import BagMessage, BagSummary, Damage, Storage, TopicSummary
from robomodel.bag.player import Player, PlayOptions
from robomodel.bag.reader import Bag, open_bag
from robomodel.bag.recorder import Recorder, RecorderStats

__all__ = [
    "Bag",
    "BagError",
    "BagFormatError",
    "BagMessage",
    "BagSummary",
    "BagWriteError",
    "BagWriter",
    "Damage",
    "McapFolderWriter",
    "PlayOptions",
    "Player",
    "Recorder",
    "RecorderStats",
    "Ros1BagWriter",
    "SplitPolicy",
    "Sqlite3FolderWriter",
    "Storage",
    "TopicSummary",
    "open_bag",
]
