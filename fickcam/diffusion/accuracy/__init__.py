"""How accurate a result is: the measured error model every plan sizes its cells and
steps with, and the three-mesh check of a converging sequence."""
