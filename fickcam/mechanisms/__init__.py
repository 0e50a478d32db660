"""Mechanisms over ageing: the parts' material state mapped onto the cam and
four-bar models at every ageing time.
"""
