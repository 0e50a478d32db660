"""Superposition of unit-step responses over an exposure history (Duhamel's theorem):
panels over a few segments, tables over a long record, and a prism's product response."""
