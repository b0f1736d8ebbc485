"""brdf-lab: a teaching lab for BRDFs, one GLSL shader per reflection model."""

__version__ = "0.1.0"
