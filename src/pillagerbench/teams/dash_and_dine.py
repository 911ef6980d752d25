"""Dash & Dine's built-in opponents (reference §6): one script per player."""

from pillagerbench.teams.scripted import ScriptedTeam


class DashAndDineTeam(ScriptedTeam):
    scenarios = ("dash_and_dine",)


class Berries(DashAndDineTeam):
    name = "berries"
    scripts = ("berries_0.js", "berries_1.js")


class CakeBeetroot(DashAndDineTeam):
    name = "cake_beetroot"
    scripts = ("cake_beetroot_0.js", "cake_beetroot_1.js")


class MelonPumpkin(DashAndDineTeam):
    name = "melon_pumpkin"
    scripts = ("melon_pumpkin_0.js", "melon_pumpkin_1.js")


class PotatoCookie(DashAndDineTeam):
    name = "potato_cookie"
    scripts = ("potato_cookie_0.js", "potato_cookie_1.js")
