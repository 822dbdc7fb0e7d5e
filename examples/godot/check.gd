# Plays a baked flipbook with flipbook_player.shader for one frame and saves what Godot drew:
#   FLIPBOOK=DIR FLIPBOOK_POSITION=P FLIPBOOK_OUT=OUT.png godot3-runner --path examples/godot \
#       -s check.gd
# DIR holds colour.png, motion.png and flipbook.json (`motionfx bake`); P is the position in cells
# (cell index and fraction). The picture is one cell's size, drawn into a transparent viewport, so
# OUT.png holds the premultiplied colour and alpha. (The settings come in the environment: Godot
# 3.2 takes a path among its arguments for a project or scene to run.)
extends SceneTree

var viewport
var out_path = ""
var frames = 0
var done = false

func fail(message):
	printerr("check.gd: " + message)
	quit(1)
	done = true

func load_texture(path):
	var image = Image.new()
	if image.load(path) != OK:
		return null
	# Half floats: the values as stored, which Godot's GLES3 renderer would otherwise decode from
	# sRGB when it samples an 8-bit texture (the motion vectors must never be).
	image.convert(Image.FORMAT_RGBAH)
	var texture = ImageTexture.new()
	texture.create_from_image(image, 0) # no filter, mipmaps or repeat
	return texture

func _init():
	var dir = OS.get_environment("FLIPBOOK")
	var position = float(OS.get_environment("FLIPBOOK_POSITION"))
	out_path = OS.get_environment("FLIPBOOK_OUT")
	if dir == "" or out_path == "":
		fail("set FLIPBOOK (the bake's folder) and FLIPBOOK_OUT (the picture to write)")
		return
	var file = File.new()
	if file.open(dir + "/flipbook.json", File.READ) != OK:
		fail("cannot read " + dir + "/flipbook.json")
		return
	var parsed = JSON.parse(file.get_as_text())
	file.close()
	if parsed.error != OK:
		fail("flipbook.json is not JSON")
		return
	var meta = parsed.result
	var colour = load_texture(dir + "/colour.png")
	var motion = load_texture(dir + "/motion.png")
	if colour == null or motion == null:
		fail("cannot load the sheets in " + dir)
		return
	var cell = Vector2(meta["cell"]["width"], meta["cell"]["height"])
	var material = ShaderMaterial.new()
	material.shader = load("res://flipbook_player.shader")
	material.set_shader_param("colour_sheet", colour)
	material.set_shader_param("motion_sheet", motion)
	material.set_shader_param("grid", Vector2(meta["grid"]["columns"], meta["grid"]["rows"]))
	material.set_shader_param("cells", float(meta["cells"]))
	material.set_shader_param("motion_scale", float(meta["motion_vectors"]["scale"]))
	material.set_shader_param("position", position)
	material.set_shader_param("loop", bool(meta["loop"]["on"]))
	print("godot: loaded ", colour.get_width(), "x", colour.get_height(), " sheet of ",
		meta["cells"], " cells; drawing position ", position)

	viewport = Viewport.new()
	viewport.size = cell
	viewport.transparent_bg = true
	viewport.hdr = false # an 8-bit target: the values drawn, unconverted
	viewport.usage = Viewport.USAGE_2D
	viewport.render_target_v_flip = true
	viewport.render_target_update_mode = Viewport.UPDATE_ALWAYS
	var rect = ColorRect.new()
	rect.rect_size = cell
	rect.material = material
	viewport.add_child(rect)
	get_root().add_child(viewport)

func _idle(_delta):
	if done:
		return true
	frames += 1
	if frames < 4:
		return false
	var image = viewport.get_texture().get_data()
	if image == null or image.get_width() == 0:
		fail("the viewport drew nothing")
		return true
	image.convert(Image.FORMAT_RGBA8)
	if image.save_png(out_path) != OK:
		fail("cannot write " + out_path)
		return true
	print("godot: drew a ", image.get_width(), "x", image.get_height(), " frame into ", out_path)
	quit(0)
	done = true
	return true
