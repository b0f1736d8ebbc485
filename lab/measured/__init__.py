"""Measured BRDFs: MERL tables, the `measured` model, fitting and spherical harmonics.

Real measured data (the MERL BRDF database, Matusik et al. 2003) is downloaded from
https://www.merl.com/brdf/ under MERL's terms; this project ships none of it and makes its
own tables with `brdf-lab tabulate`.
"""
