"""The runtime layer: messages, topics, parameters and nodes, in-process or over Zenoh."""
