"""A view that exists only in the test suite: it proves a new view is its module alone."""
