"""What a film or a glTF file shows, without GL: the table, the room and lamp, materials and meshes, cameras, textures, the cue, ball colours."""
