"""Whether the physics says on stderr, the first time, that it is compiling itself
(billiards.physics.compiled): the commands' --quiet turns it off. A module of its own,
so that a command sets it without loading numba."""

announce = True
