"""The physics: beam and drive parameters, the discrete elastica, modes, quasi-static states,
shapes, the one-mode surrogate, the canonical second-order system and the paper's measures."""
