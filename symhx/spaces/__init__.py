"""tmp"""
from symhx.spaces._classes import *  # noqa
from symhx.spaces._dist import *  # noqa
from symhx.spaces._critical import *  # noqa
from symhx.spaces.study import *  # noqa
from symhx.spaces.symbolic import *  # noqa
