"""Image-based lighting: the reflection equation under an environment, by Monte Carlo on the GPU."""
