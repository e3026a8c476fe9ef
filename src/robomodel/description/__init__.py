"""The description layer: the URDF model, its parser, writer and validation, and ROS packages."""
