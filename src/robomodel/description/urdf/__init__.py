"""URDF XML reading and writing."""
