"""Files: the .htl project file and its media, atomic writes, import and export through the
format plugins, the clipboard, sound-to-haptics conversion and a project's summary.
"""
