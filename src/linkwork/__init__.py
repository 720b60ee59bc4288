"""linkwork: kinematics of planar mechanisms."""
