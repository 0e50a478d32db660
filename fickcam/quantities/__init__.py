"""Quantities with units: parsing written values into SI, the pydantic types of
scene values, and the plausibility rules that catch a unit slip (shared by the
scene, the climate records and the command line).
"""
