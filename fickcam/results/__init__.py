"""Results: the schema table, the Dataset built from it, result files, queries,
exports, limits and the result's size.
"""
