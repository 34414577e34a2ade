"""A case for another program: :mod:`.opensees` writes it as a standalone OpenSeesPy model whose running part
is :mod:`.opensees_script`."""
