"""Building a MuJoCo model (``mujoco.MjSpec``) from robomodel's URDF model and a world."""
