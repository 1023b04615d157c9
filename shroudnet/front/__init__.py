"""The faces of the package: the command line, the figures (the only code that imports
matplotlib, lazily), the benchmark, the terminal progress displays, and the studies as the
package offers them with a terminal display and a folder store by default. The front may
import every layer; nothing imports the front but ``shroudnet`` itself and
``__main__``.
"""
