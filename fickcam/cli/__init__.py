"""The ``fickcam`` command line: arguments, subcommands and the text they print.
"""
