"""Elasticity of the parts: contact deflection of the cam plate and hygrothermal
(swelling) stresses, plane stress by finite elements (scikit-fem, imported only in
:mod:`fickcam.elastic.fem`). Computed only when a scene asks (``cam.elastic: true``,
``linkage.elastic: true``)."""
