"""The seed's rolling model: every moving ball rolls, slowing at mu g (MODEL.md). Its
closed-form motion, its contact times (walls, pairs, pockets) and its law."""
