"""The only GL code: the context, the renderer and its passes."""
