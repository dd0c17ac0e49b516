"""A Blender material's diffuse reflectance and emission, as dynrad reads them (see the
add-on's module comment: Principled BSDF's Base Color, Emission x Emission Strength; an
Emission shader; the viewport colour without nodes)."""

MAX_REFLECTANCE = 0.95  # what the light operator lowers reflectance to
DEFAULT_REFLECTANCE = 0.5  # faces without a material, as dynrad's importers do


def _socket_value(node, name, default):
    socket = node.inputs.get(name)
    return socket.default_value if socket is not None else default


def material_values(material, clamp=True):
    """(reflectance rgb, emission rgb) of a Blender material; see the add-on's module
    comment. clamp=False leaves reflectance as the material has it (the design operator
    refuses 1 or more instead of lowering it)."""
    if material is None:
        return (DEFAULT_REFLECTANCE,) * 3, (0.0, 0.0, 0.0)
    reflectance, emission = tuple(material.diffuse_color[:3]), (0.0, 0.0, 0.0)
    if material.use_nodes and material.node_tree:
        output = next((n for n in material.node_tree.nodes if n.type == "OUTPUT_MATERIAL" and n.is_active_output),
                      None)
        surface = output.inputs["Surface"] if output else None
        shader = surface.links[0].from_node if surface is not None and surface.is_linked else None
        if shader is not None and shader.type == "BSDF_PRINCIPLED":
            reflectance = tuple(_socket_value(shader, "Base Color", (0.5, 0.5, 0.5, 1))[:3])
            strength = _socket_value(shader, "Emission Strength", 1.0)
            emission = tuple(c * strength for c in _socket_value(shader, "Emission", (0, 0, 0, 1))[:3])
        elif shader is not None and shader.type == "EMISSION":
            reflectance = (0.0, 0.0, 0.0)
            strength = _socket_value(shader, "Strength", 1.0)
            emission = tuple(c * strength for c in _socket_value(shader, "Color", (1, 1, 1, 1))[:3])
    reflectance = tuple(max(float(c), 0.0) for c in reflectance)
    if clamp:
        reflectance = tuple(min(c, MAX_REFLECTANCE) for c in reflectance)
    emission = tuple(max(float(c), 0.0) for c in emission)
    return reflectance, emission
