"""The climate a part lives in: constant segments, chamber and weather records, and
the standard damp-heat tests, as temperature and relative humidity over time.
"""
