"""Instantaneous kinematics of the relative motion of any link i with respect to any link j."""
