"""The scene: a YAML file read with line numbers, validated section by section into SI
values, and shown back to a person.
"""
