"""The views' Qt widgets: one module per view, named like its lab/views/ module.

Each `lab/views/<name>.py` names its widget here (`ViewSpec.widget`,
"lab.app.views.<name>:<Class>"); the window builds a dock for every registered view from
that, so a new view needs no edit outside its own files. `base` holds what they share.
"""
