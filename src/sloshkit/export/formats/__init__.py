"""Controller file formats: one module per format, each with a writer and a parser.

Every writer puts ``# key: value`` metadata lines (or YAML/URScript comments) first and writes
atomically; every parser returns what the round trip needs to rebuild the container's motion.
"""
