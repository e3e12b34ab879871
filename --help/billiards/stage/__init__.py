"""What a film or a glTF file shows, without GL: geometry, materials, cameras, textures, the cue, ball colours."""
