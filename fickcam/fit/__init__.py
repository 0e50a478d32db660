"""Calibrate a material's moisture parameters from ASTM D5229 weight-gain data."""
