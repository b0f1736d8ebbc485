"""The web lab (WebGL2 page over the same shader files) and the lecture slides."""
