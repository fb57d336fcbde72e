# Layer: contact. Modules and the objects of the modules each one uses.
MODULES += contact
$(OBJDIR)/contact.o: $(OBJDIR)/element_catalogue.o $(OBJDIR)/element_types.o $(OBJDIR)/kinds.o $(OBJDIR)/model.o
