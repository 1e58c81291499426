"""``python -m orccad_app``: the ``orccad`` command, for environments without the script."""


from orccad_app.cli import entry_point

if __name__ == "__main__":
    entry_point()
