"""One run of a scene: its parts, the order of the work, and the run's resources.
"""
