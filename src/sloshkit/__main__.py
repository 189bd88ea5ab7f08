"""``python -m sloshkit``: the command line."""

from sloshkit.entry import main

if __name__ == "__main__":
    main()
