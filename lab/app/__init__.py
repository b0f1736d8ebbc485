"""The desktop lab: a Qt window with every view of the models, updating live."""
