"""Helpers the workspace's tests share: process groups, a virtual screen, X window dumps."""
