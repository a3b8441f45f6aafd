"""`partgen check`: does the kit print, assemble and turn? Interference over the motion, fits,
gear meshes, clearances, printability and build plates."""
