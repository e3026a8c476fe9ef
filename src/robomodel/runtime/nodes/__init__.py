"""The standard nodes of the description workflow: joint and robot state publishers."""
