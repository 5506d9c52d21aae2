"""The current OpenGL context's functions through ctypes, and the GL enumerants, for the
experiments here that run shaders of their own in a VTK window (compute_traversal.py)."""

import ctypes
from ctypes import POINTER, c_char_p, c_float, c_int, c_ssize_t, c_ubyte, c_uint, c_void_p

# GL entry points: name -> (result, arguments).
_SIGNATURES = {
    "glCreateShader": (c_uint, [c_uint]),
    "glShaderSource": (None, [c_uint, c_int, POINTER(c_char_p), c_void_p]),
    "glCompileShader": (None, [c_uint]),
    "glGetShaderiv": (None, [c_uint, c_uint, POINTER(c_int)]),
    "glGetShaderInfoLog": (None, [c_uint, c_int, c_void_p, c_char_p]),
    "glCreateProgram": (c_uint, []),
    "glAttachShader": (None, [c_uint, c_uint]),
    "glLinkProgram": (None, [c_uint]),
    "glGetProgramiv": (None, [c_uint, c_uint, POINTER(c_int)]),
    "glGetProgramInfoLog": (None, [c_uint, c_int, c_void_p, c_char_p]),
    "glUseProgram": (None, [c_uint]),
    "glGetUniformLocation": (c_int, [c_uint, c_char_p]),
    "glUniformMatrix4fv": (None, [c_int, c_int, c_ubyte, POINTER(c_float)]),
    "glUniform2f": (None, [c_int, c_float, c_float]),
    "glUniform1i": (None, [c_int, c_int]),
    "glUniform1ui": (None, [c_int, c_uint]),
    "glUniform1f": (None, [c_int, c_float]),
    "glGenBuffers": (None, [c_int, POINTER(c_uint)]),
    "glBindBuffer": (None, [c_uint, c_uint]),
    "glBufferData": (None, [c_uint, c_ssize_t, c_void_p, c_uint]),
    "glBindBufferBase": (None, [c_uint, c_uint, c_uint]),
    "glGenTextures": (None, [c_int, POINTER(c_uint)]),
    "glBindTexture": (None, [c_uint, c_uint]),
    "glActiveTexture": (None, [c_uint]),
    "glTexBuffer": (None, [c_uint, c_uint, c_uint]),
    "glTexImage2D": (None, [c_uint, c_int, c_int, c_int, c_int, c_int, c_uint, c_uint, c_void_p]),
    "glTexImage3D": (None, [c_uint, c_int, c_int, c_int, c_int, c_int, c_int, c_uint, c_uint,
                            c_void_p]),
    "glTexParameteri": (None, [c_uint, c_uint, c_int]),
    "glBindImageTexture": (None, [c_uint, c_uint, c_int, c_ubyte, c_int, c_uint, c_uint]),
    "glClearTexImage": (None, [c_uint, c_int, c_uint, c_uint, c_void_p]),
    "glClearBufferData": (None, [c_uint, c_uint, c_uint, c_uint, c_void_p]),
    "glGenFramebuffers": (None, [c_int, POINTER(c_uint)]),
    "glBindFramebuffer": (None, [c_uint, c_uint]),
    "glFramebufferTexture2D": (None, [c_uint, c_uint, c_uint, c_uint, c_int]),
    "glCheckFramebufferStatus": (c_uint, [c_uint]),
    "glViewport": (None, [c_int, c_int, c_int, c_int]),
    "glEnable": (None, [c_uint]),
    "glDisable": (None, [c_uint]),
    "glBlendFunc": (None, [c_uint, c_uint]),
    "glBlendEquation": (None, [c_uint]),
    "glColorMask": (None, [c_ubyte] * 4),
    "glGenVertexArrays": (None, [c_int, POINTER(c_uint)]),
    "glBindVertexArray": (None, [c_uint]),
    "glDrawArrays": (None, [c_uint, c_int, c_int]),
    "glDispatchCompute": (None, [c_uint, c_uint, c_uint]),
    "glMemoryBarrier": (None, [c_uint]),
    "glFinish": (None, []),
    "glGetTexImage": (None, [c_uint, c_int, c_uint, c_uint, c_void_p]),
    "glGetBufferSubData": (None, [c_uint, c_ssize_t, c_ssize_t, c_void_p]),
    "glPixelStorei": (None, [c_uint, c_int]),
}

# The GL enumerants used here.
VERTEX_SHADER, FRAGMENT_SHADER, COMPUTE_SHADER = 0x8B31, 0x8B30, 0x91B9
COMPILE_STATUS, LINK_STATUS = 0x8B81, 0x8B82
SHADER_STORAGE_BUFFER, TEXTURE_BUFFER, STATIC_DRAW = 0x90D2, 0x8C2A, 0x88E4
TEXTURE_2D, TEXTURE_3D, TEXTURE_2D_ARRAY, TEXTURE0 = 0x0DE1, 0x806F, 0x8C1A, 0x84C0
R32UI, R32I, R32I_FORMAT, RGBA32F = 0x8236, 0x8235, 0x8D94, 0x8814
R32F, RGB32F, RGBA32UI = 0x822E, 0x8815, 0x8D70
RGBA, FLOAT, UNSIGNED_INT, INT = 0x1908, 0x1406, 0x1405, 0x1404
MIN_FILTER, MAG_FILTER, WRAP_S, WRAP_T, WRAP_R = 0x2801, 0x2800, 0x2802, 0x2803, 0x8072
LINEAR, NEAREST, CLAMP_TO_EDGE = 0x2601, 0x2600, 0x812F
FRAMEBUFFER, COLOR_ATTACHMENT0, FRAMEBUFFER_COMPLETE = 0x8D40, 0x8CE0, 0x8CD5
READ_WRITE, ALL_BARRIER_BITS, PACK_ALIGNMENT = 0x88BA, 0xFFFFFFFF, 0x0D05
DEPTH_TEST, SCISSOR_TEST, BLEND, PROGRAM_POINT_SIZE, FUNC_ADD, POINTS = (
    0x0B71, 0x0C11, 0x0BE2, 0x8642, 0x8006, 0x0000)


class GL:
    """The current context's GL functions, through glXGetProcAddress or eglGetProcAddress."""

    def __init__(self, egl: bool):
        if egl:
            library = ctypes.CDLL("libEGL.so.1")
            lookup = library.eglGetProcAddress
        else:
            library = ctypes.CDLL("libGL.so.1")
            lookup = library.glXGetProcAddressARB
        lookup.restype = c_void_p
        lookup.argtypes = [c_char_p]
        for name, (result, arguments) in _SIGNATURES.items():
            address = lookup(name.encode())
            if not address:
                raise RuntimeError(f"the context has no {name}")
            setattr(self, name[2:], ctypes.CFUNCTYPE(result, *arguments)(address))

    def _check(self, get_status, get_log, name: int, status_kind: int) -> None:
        status = c_int()
        get_status(name, status_kind, ctypes.byref(status))
        if not status.value:
            log = ctypes.create_string_buffer(10000)
            get_log(name, 10000, None, log)
            raise RuntimeError(log.value.decode())

    def shader(self, kind: int, source: str) -> int:
        shader = self.CreateShader(kind)
        text = c_char_p(source.encode())
        self.ShaderSource(shader, 1, ctypes.byref(text), None)
        self.CompileShader(shader)
        self._check(self.GetShaderiv, self.GetShaderInfoLog, shader, COMPILE_STATUS)
        return shader

    def program(self, *stages) -> int:
        program = self.CreateProgram()
        for kind, source in stages:
            self.AttachShader(program, self.shader(kind, source))
        self.LinkProgram(program)
        self._check(self.GetProgramiv, self.GetProgramInfoLog, program, LINK_STATUS)
        return program

    def name(self, generate) -> int:
        value = c_uint()
        generate(1, ctypes.byref(value))
        return value.value
