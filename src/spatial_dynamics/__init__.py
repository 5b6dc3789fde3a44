"""Python side of spatial_dynamics: a client of the node's services (spatial_dynamics.client)."""
