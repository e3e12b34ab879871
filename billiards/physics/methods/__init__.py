"""The methods a run is simulated by (entry: each run to the engine that serves it;
naive: the seed's stepped method)."""
