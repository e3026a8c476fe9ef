"""The ``robomodel`` command line: one sub-module per verb, each with ``register(subparsers)``."""
