"""Parts as drawn: a planform (outer loop and holes) read from a DXF drawing or written in
a scene, checked, measured (area, centre, second moments) and written back as DXF.

Pure geometry: nothing here knows a scene or a mechanism. ``planform`` (the value and
its checks, numpy and matplotlib's point-in-polygon), ``pieces`` (pieces joined end to
end into loops), ``dxfread`` and ``dxfwrite`` (the only modules that import ezdxf, the
``dxf`` extra).
"""
