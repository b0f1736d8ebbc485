"""A check kind that exists only in the test suite: it proves a new kind is its module alone."""
